// Heavier rod-dynamics studies (ctest label `slow`).
#include <gtest/gtest.h>

#include "cosserat/dynamics.hpp"
#include "dynamics_models.hpp"

namespace tcasim::cosserat::testing {
namespace {
TEST(RodDynamicsSlow, Placeholder) { SUCCEED(); }
}  // namespace
}  // namespace tcasim::cosserat::testing
