// Rod dynamics with strings anchored inside the body and spline routings (docs/conventions.md
// "Rod dynamics (shooting method)"): the anchors and spline knots are grid nodes; a string
// outside its span carries nothing; the routing is read on each step's side of a knot. Held
// against the static shooting solver (which handles anchors and kinks by strain jumps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/shooting.hpp"
#include "dynamics_at_rest.hpp"
#include "dynamics_models.hpp"
#include "rod/scenario.hpp"

namespace tcasim::cosserat::testing {
namespace {

constexpr double kTightTolerance = 1e-12;

/// The steel cantilever of dynamics_models.hpp with the strings of `kind`:
/// - "anchored": a straight string at x = 0.8 mm over [0, 0.3] (2 N), one at y = 0.7 mm
///   over [0.1, 0.4] (1 N, both ends inside the body) and a slack one over [0.2, 0.45];
/// - "slack": two slack straight strings over [0, 0.25] and [0.2, 0.45] (no tension: the
///   residual-only path; their elongations are the bending's alone);
/// - "linear": a disk-routed string (linear spline, kinks at 0.2 and 0.35 m, 2 N) and a
///   straight one anchored at 0.25 m (1 N);
/// - "cubic": a cubic spline converging from 0.9 mm to 0.4 mm (2 N), with a slight y drift.
rod::RodModel steel_with(const std::string& kind) {
  nlohmann::json doc = nlohmann::json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "steel-strings",
    "body": {"length_m": 0.5, "section": {"shape": "circle", "diameter_m": 0.002},
             "material": {"youngs_modulus_Pa": 200e9, "poisson_ratio": 0.25,
                          "density_kg_m3": 8000}},
    "actuators": []})");
  auto tension = [](double T) { return nlohmann::json{{"type", "tension"}, {"tension_N", T}}; };
  nlohmann::json& acts = doc["actuators"];
  if (kind == "anchored") {
    acts.push_back({{"name", "a"},
                    {"routing", {{"type", "straight"}, {"offset_m", {0.8e-3, 0.0}}}},
                    {"span_m", {0.0, 0.3}},
                    {"drive", tension(2.0)}});
    acts.push_back({{"name", "b"},
                    {"routing", {{"type", "straight"}, {"offset_m", {0.0, 0.7e-3}}}},
                    {"span_m", {0.1, 0.4}},
                    {"drive", tension(1.0)}});
    // Slack (the residual-only path integrates its elongation over its span alone).
    acts.push_back({{"name", "slack"},
                    {"routing", {{"type", "straight"}, {"offset_m", {-0.6e-3, 0.0}}}},
                    {"span_m", {0.2, 0.45}},
                    {"drive", tension(0.0)}});
  } else if (kind == "slack") {
    for (const double s0 : {0.0, 0.2}) {
      acts.push_back({{"name", s0 == 0.0 ? "slack-base" : "slack-inner"},
                      {"routing", {{"type", "straight"}, {"offset_m", {0.0, 0.8e-3}}}},
                      {"span_m", {s0, s0 + 0.25}},
                      {"drive", tension(0.0)}});
    }
  } else if (kind == "linear") {
    acts.push_back(
        {{"name", "disks"},
         {"routing",
          {{"type", "spline"},
           {"interpolation", "linear"},
           {"s_m", {0.0, 0.2, 0.35, 0.5}},
           {"offset_m", {{0.8e-3, 0.0}, {0.6e-3, 0.2e-3}, {0.5e-3, 0.2e-3}, {0.4e-3, 0.0}}}}},
         {"drive", tension(2.0)}});
    acts.push_back({{"name", "short"},
                    {"routing", {{"type", "straight"}, {"offset_m", {-0.7e-3, 0.0}}}},
                    {"span_m", {0.0, 0.25}},
                    {"drive", tension(1.0)}});
  } else {
    acts.push_back(
        {{"name", "converging"},
         {"routing",
          {{"type", "spline"},
           {"interpolation", "cubic"},
           {"s_m", {0.0, 0.15, 0.3, 0.5}},
           {"offset_m", {{0.9e-3, 0.0}, {0.75e-3, 0.05e-3}, {0.6e-3, 0.1e-3}, {0.4e-3, 0.1e-3}}}}},
         {"drive", tension(2.0)}});
  }
  return rod::parse_scenario(doc);
}

// At rest the dynamic BVP is the static one on the dynamics' grid: with the anchors and knots
// as nodes it converges at order 4 to the static shooting solver, down to round-off (a string
// counted outside its span, or a kink read on the wrong side, would leave an O(1) or O(h)
// error).
TEST(RodDynamicsStrings, AtRestTheyReproduceTheStaticSolverAtOrderFour) {
  for (const std::string kind : {"anchored", "slack", "linear", "cubic"}) {
    SCOPED_TRACE(kind);
    const rod::RodModel m = steel_with(kind);
    const rod::Loads loads = sag_loads(m, 0.010);
    const Solution ref = static_reference(m, loads, 128, kTightTolerance);
    const Eigen::Vector3d p_ref = ref.tip_state.head<3>();
    const auto d = expect_rest_converges_at_order_four(m, loads, p_ref, m.interior_knots(),
                                                       kind.c_str(), kTightTolerance);
    ASSERT_TRUE(d);
    // The elongations (path length over the span minus the rest length) are the static
    // solver's.
    const std::vector<double> e = d->elongations_m();
    ASSERT_EQ(e.size(), ref.elongations_m.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      EXPECT_NEAR(e[i], ref.elongations_m[i], 1e-11 * m.length_m) << "string " << i;
    }
  }
}

// The static equilibrium stays at rest under unchanged loads.
TEST(RodDynamicsStrings, AStepFromRestStaysAtRest) {
  for (const std::string kind : {"anchored", "slack", "linear", "cubic"}) {
    SCOPED_TRACE(kind);
    const rod::RodModel m = steel_with(kind);
    const rod::Loads loads = sag_loads(m, 0.010);
    DynamicsOptions o;
    o.steps = 20;
    o.dt_s = 1e-3;
    RodDynamics d(m, o);
    ASSERT_TRUE(d.initialize(loads).converged());
    const Eigen::Vector3d p0 = d.tip_position_W_m();
    const std::vector<double> e0 = d.elongations_m();
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(d.step(loads).converged());
    EXPECT_LT((d.tip_position_W_m() - p0).norm(), 1e-12 * m.length_m);
    const std::vector<double> e = d.elongations_m();
    for (std::size_t i = 0; i < e.size(); ++i) EXPECT_NEAR(e[i], e0[i], 1e-12 * m.length_m) << i;
    EXPECT_LT(d.kinetic_energy_J(), 1e-20);
  }
}

}  // namespace
}  // namespace tcasim::cosserat::testing
