#pragma once
/// The shared test models (tests/support/rod_models.hpp) in the beam FE tests' namespace.
#include "support/rod_models.hpp"

namespace tcasim::beam_fe::testing {
using namespace tcasim::test_support;  // NOLINT: test models only
}  // namespace tcasim::beam_fe::testing
