#pragma once
/// The shared test models (tests/support/rod_models.hpp) in the beam FE tests' namespace,
/// and the FE tests' solve helpers.
#include "beam_fe/beam_fe.hpp"
#include "support/rod_models.hpp"

namespace tcasim::beam_fe::testing {
using namespace tcasim::test_support;  // NOLINT: test models only

/// FE options for the tests: Newton's relative tolerance tightened from 1e-10 to 1e-12 so
/// that solver error stays below the checks of constant-strain states.
inline Options options(int elements, int order = 2) {
  Options o;
  o.elements = elements;
  o.order = order;
  o.tolerance_rel = 1e-12;
  return o;
}

/// A solve's summary and final state.
struct Solved {
  Summary summary;
  State state;
};

/// Solves `model` from its reference configuration.
inline Solved run(const rod::RodModel& model, const Options& opt) {
  Solved s;
  s.summary = solve(model, opt, s.state);
  return s;
}

}  // namespace tcasim::beam_fe::testing
