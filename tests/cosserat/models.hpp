#pragma once
/// The shared test models (tests/support/rod_models.hpp) in the shooting-solver tests' namespace.
#include "support/rod_models.hpp"

namespace tcasim::cosserat::testing {
using namespace tcasim::test_support;  // NOLINT: test models only
}  // namespace tcasim::cosserat::testing
