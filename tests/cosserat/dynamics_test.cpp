// Rod dynamics by multiple shooting (cosserat/dynamics.hpp): the static initialization
// against the static shooting solver, rest, the spatial order of a time step, energy.
#include "cosserat/dynamics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "common/error.hpp"
#include "cosserat/shooting.hpp"
#include "dynamics_at_rest.hpp"
#include "dynamics_models.hpp"
#include "support/convergence.hpp"

namespace tcasim::cosserat::testing {
namespace {

/// Residual tolerance of the round-off comparisons (the default 1e-10 leaves solution errors
/// near 1e-11 m on these rods).
constexpr double kTightTolerance = 1e-12;

/// Tip position of the static shooting solver with RK8 on 64 steps.
Eigen::Vector3d static_reference_tip(const rod::RodModel& m, const rod::Loads& loads) {
  return static_reference(m, loads, 64, kTightTolerance).tip_state.head<3>();
}

/// The steel cantilever with two tensioned strings (a straight one and a helix), gravity
/// and a tip weight: exercises the section's constitutive solve with strings.
rod::RodModel steel_with_strings() {
  rod::RodModel m = steel_cantilever();
  test_support::add_tension_string(m, "straight", 0.8e-3, 0.0, 2.0);
  test_support::add_tension_string(m, "helix", 0.0, 0.7e-3, 1.0, 1, 2.0);
  return m;
}

// At rest the dynamic BVP is the static one with this solver's states (N, M include the
// string tensions) and RK4 on the same grid: it converges at order 4 to the static shooting
// solution, down to round-off.
TEST(RodDynamics, StaticInitializationConvergesToTheShootingSolutionAtOrderFour) {
  for (const bool strings : {false, true}) {
    SCOPED_TRACE(strings ? "with strings" : "plain cantilever");
    const rod::RodModel m = strings ? steel_with_strings() : steel_cantilever();
    const rod::Loads loads = sag_loads(m, 0.020);
    const Eigen::Vector3d p_ref = static_reference_tip(m, loads);
    std::vector<double> h, err;
    for (const int n : {10, 20, 40, 80}) {
      DynamicsOptions o;
      o.steps = n;
      o.tolerance = kTightTolerance;
      RodDynamics d(m, o);
      const DynamicsSummary s = d.initialize(loads);
      ASSERT_TRUE(s.converged()) << s.message;
      h.push_back(m.length_m / n);
      err.push_back((d.tip_position_W_m() - p_ref).norm());
    }
    test_support::ExpectOrderInBracket(h, err, 4.0, 0.5);
    // Round-off level at a fine grid (1e-11 of L: the sag is 0.13 L).
    DynamicsOptions o;
    o.steps = 320;
    o.tolerance = kTightTolerance;
    RodDynamics d(m, o);
    ASSERT_TRUE(d.initialize(loads).converged());
    EXPECT_LT((d.tip_position_W_m() - p_ref).norm(), 1e-11 * m.length_m);
  }
}

// The static equilibrium is a fixed point of the time step: with unchanged loads the rod
// stays where it is (the history terms cancel, c0 + c1 + c2 = 0).
TEST(RodDynamics, AStepFromRestUnderUnchangedLoadsStaysAtRest) {
  const rod::RodModel m = steel_with_strings();
  const rod::Loads loads = sag_loads(m, 0.020);
  DynamicsOptions o;
  o.steps = 20;
  o.dt_s = 1e-3;
  RodDynamics d(m, o);
  ASSERT_TRUE(d.initialize(loads).converged());
  const Eigen::Vector3d p0 = d.tip_position_W_m();
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(d.step(loads).converged());
  EXPECT_LT((d.tip_position_W_m() - p0).norm(), 1e-12 * m.length_m);
  // Kinetic energy against the elastic energy scale of the sag (about 1e-2 J).
  EXPECT_LT(d.kinetic_energy_J(), 1e-20);
}

/// Tip after `steps` time steps of the released cantilever (20 g tip weight removed at t = 0,
/// gravity on) with N grid steps.
Eigen::Vector3d released_tip(
    int n, int steps, double dt, double alpha = -0.2,
    DynamicsOptions::SpatialScheme scheme = DynamicsOptions::SpatialScheme::kRk4) {
  const rod::RodModel m = steel_cantilever();
  DynamicsOptions o;
  o.scheme = scheme;
  o.steps = n;
  o.dt_s = dt;
  o.alpha = alpha;
  RodDynamics d(m, o);
  EXPECT_TRUE(d.initialize(sag_loads(m, 0.020)).converged());
  const rod::Loads released = sag_loads(m, 0.0);
  for (int k = 0; k < steps; ++k) {
    const DynamicsSummary s = d.step(released);
    EXPECT_TRUE(s.converged()) << s.message;
    if (!s.converged()) break;
  }
  return d.tip_position_W_m();
}

// The spatial scheme: RK4 on the fixed grid, the history stored at its stage points, is
// fourth order in s at a fixed time step (RK4 applied to the causal system of all steps).
TEST(RodDynamics, TheTimeStepIsFourthOrderInS) {
  const int steps = 10;
  const double dt = 2e-3;
  const Eigen::Vector3d ref = released_tip(160, steps, dt);
  std::vector<double> h, err;
  for (const int n : {10, 20, 40}) {
    h.push_back(0.5 / n);
    err.push_back((released_tip(n, steps, dt) - ref).norm());
  }
  test_support::ExpectOrderInBracket(h, err, 4.0, 0.5);
}

// The comparison scheme (forward Euler along s) is first order on the same problem.
TEST(RodDynamics, TheEulerSchemeAlongSIsFirstOrder) {
  const int steps = 10;
  const double dt = 2e-3;
  const Eigen::Vector3d ref = released_tip(160, steps, dt);
  std::vector<double> h, err;
  for (const int n : {20, 40, 80}) {
    h.push_back(0.5 / n);
    err.push_back(
        (released_tip(n, steps, dt, -0.2, DynamicsOptions::SpatialScheme::kEuler) - ref).norm());
  }
  test_support::ExpectOrderInBracket(h, err, 1.0, 0.5);
}

// Released cantilever without damping: total energy (kinetic + strain + gravity) never
// grows (BDF-alpha with alpha > -0.5 dissipates); with Kelvin-Voigt damping it falls faster.
TEST(RodDynamics, EnergyOfTheReleasedCantileverDoesNotGrowAndDampingDissipates) {
  const rod::RodModel m = steel_cantilever();
  double lost[2] = {0.0, 0.0};
  for (const int damped : {0, 1}) {
    DynamicsOptions o;
    o.steps = 20;
    o.dt_s = 2e-3;
    o.viscosity_Pa_s = damped ? 2e7 : 0.0;
    RodDynamics d(m, o);
    ASSERT_TRUE(d.initialize(sag_loads(m, 0.020)).converged());
    const rod::Loads released = sag_loads(m, 0.0);
    ASSERT_TRUE(d.step(released).converged());
    double e_prev = d.kinetic_energy_J() + d.potential_energy_J();
    const double e0 = e_prev;
    for (int k = 0; k < 100; ++k) {
      ASSERT_TRUE(d.step(released).converged());
      const double e = d.kinetic_energy_J() + d.potential_energy_J();
      EXPECT_LE(e, e_prev + 1e-12 * std::abs(e0)) << "step " << k;
      e_prev = e;
    }
    lost[damped] = e0 - e_prev;
  }
  EXPECT_GT(lost[1], 2.0 * lost[0]);
}

// A varying body (taper, a jump of the diameter, a growing precurvature): the grid has a node
// at the jump, each piece is smooth, so the static initialization still converges at order 4
// to the static shooting solver (which steps onto the same breakpoint), down to round-off.
TEST(RodDynamics, TaperedRodAtRestReproducesTheStaticSolverAtOrderFour) {
  const rod::RodModel m = tapered_steel_cantilever();
  ASSERT_FALSE(m.uniform_body());
  const rod::Loads loads = sag_loads(m, 0.010);
  const Eigen::Vector3d p_ref =
      static_reference(m, loads, 128, kTightTolerance).tip_state.head<3>();
  // The jump at s = 0.3 is a grid node.
  EXPECT_TRUE(
      expect_rest_converges_at_order_four(m, loads, p_ref, {0.3}, "tapered rod", kTightTolerance));
}

// The tapered rod released from its sag: every step converges, the rod moves, the energy
// never grows, and the viscosity profile (1e7 to 3e7 Pa s along s) dissipates more than its
// smallest value taken constant and less than its largest.
TEST(RodDynamics, TaperedRodWithAViscosityProfileIsReleasedAndDissipates) {
  const rod::RodModel m = tapered_steel_cantilever();
  const std::optional<double> viscosities[3] = {1e7, std::nullopt, 3e7};
  double lost[3] = {0.0, 0.0, 0.0};
  for (int run = 0; run < 3; ++run) {
    DynamicsOptions o;
    o.steps = 20;
    o.dt_s = 2e-3;
    o.viscosity_Pa_s = viscosities[run];  // unset: the model's profile
    RodDynamics d(m, o);
    ASSERT_TRUE(d.initialize(sag_loads(m, 0.010)).converged());
    const Eigen::Vector3d p0 = d.tip_position_W_m();
    const rod::Loads released = sag_loads(m, 0.0);
    ASSERT_TRUE(d.step(released).converged());
    double e_prev = d.kinetic_energy_J() + d.potential_energy_J();
    const double e0 = e_prev;
    for (int k = 0; k < 50; ++k) {
      const DynamicsSummary s = d.step(released);
      ASSERT_TRUE(s.converged()) << "step " << k << ": " << s.message;
      const double e = d.kinetic_energy_J() + d.potential_energy_J();
      EXPECT_LE(e, e_prev + 1e-12 * std::abs(e0)) << "step " << k;
      e_prev = e;
    }
    // The released tip moves by a fraction of its 10 g sag (several mm).
    EXPECT_GT((d.tip_position_W_m() - p0).norm(), 1e-3);
    lost[run] = e0 - e_prev;
  }
  EXPECT_GT(lost[1], lost[0]);
  EXPECT_LT(lost[1], lost[2]);
}

TEST(RodDynamics, OptionsOutsideTheirRangeAreRefusedByName) {
  const rod::RodModel m = steel_cantilever();
  DynamicsOptions o;
  o.alpha = -0.6;
  EXPECT_THROW(
      {
        try {
          RodDynamics d(m, o);
        } catch (const InputError& e) {
          EXPECT_EQ(e.key(), "dynamics.alpha");
          throw;
        }
      },
      InputError);
  o = DynamicsOptions{};
  o.steps = 40;
  o.intervals = 7;
  EXPECT_THROW(RodDynamics(m, o), InputError);
}

}  // namespace
}  // namespace tcasim::cosserat::testing
