// Variable time steps of the FE dynamics (beam_fe/dynamics.hpp; docs/conventions.md "Variable
// time steps"): the local error estimate against the actual one-step error, its order, undo of
// a step, and constant steps unchanged by set_time_step.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "beam_fe/dynamics.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "support/convergence.hpp"
#include "support/rod_models.hpp"

namespace tcasim::beam_fe {
namespace {

using test_support::sag;

/// The smooth transverse tip load F(t) = F0 (1 - cos(2 pi t / 0.04 s)) on the loads of `m`
/// (gravity off): at rest at t = 0 with zero force and force rate, so the start is consistent
/// (a_0 = vdot_0). Bending only: a torsional or axial load drives the mesh's stiff modes
/// (omega dt ~ 50 at dt 0.4 ms), which are not resolved and whose one-step error is of lower
/// order (docs/conventions.md "Variable time steps").
rod::Loads smooth_loads(const rod::RodModel& m, double t) {
  rod::Loads loads = rod::Loads::from_model(m);
  const double f = 0.5 * (1.0 - std::cos(2.0 * units::kPi * t / 0.04));
  loads.tip_force_W_N = Eigen::Vector3d(-0.3 * f, 0.0, 0.0);
  return loads;
}

/// Largest nodal difference of two states, positions [m] and rotations times L.
double state_distance(const State& a, const State& b, double L) {
  double e = 0.0;
  for (std::size_t k = 0; k < a.p_W_m.size(); ++k) {
    e = std::max(e, (a.p_W_m[k] - b.p_W_m[k]).norm());
    const Eigen::Quaterniond dq = b.q_WB[k].conjugate() * a.q_WB[k];
    e = std::max(e, L * so3::log(dq).norm());
  }
  return e;
}

struct OneStep {
  double estimate, actual;
};

/// At t = 0.012 s of the smooth forcing taken in steps of dt: one step of dt (its estimate), and
/// its actual local error against 8 steps of dt / 8 from the same state (error 64 times
/// smaller).
OneStep one_step_error(double dt, double rho_inf) {
  const rod::RodModel m = test_support::steel_cantilever_till();
  DynamicsOptions o;
  o.elements = 6;
  o.dt_s = dt;
  o.rho_inf = rho_inf;
  BeamDynamics d(m, o);
  EXPECT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
  const int n = static_cast<int>(std::lround(0.012 / dt));
  for (int k = 1; k <= n; ++k) EXPECT_TRUE(d.step(smooth_loads(m, k * dt)).converged());
  const double t0 = d.time_s();
  EXPECT_TRUE(d.step(smooth_loads(m, t0 + dt)).converged());
  const State big = d.state();
  const double estimate = d.local_error_m();
  d.undo_step();
  d.set_time_step(dt / 8.0);
  for (int k = 1; k <= 8; ++k) EXPECT_TRUE(d.step(smooth_loads(m, t0 + k * dt / 8.0)).converged());
  return {estimate, state_distance(big, d.state(), m.length_m)};
}

// The estimate e = (beta - gamma/2 + 1/12) dt^2 (a_{n+1} - a_n) against the actual one-step
// error: within a factor 2 of it, and of order 3 in dt (local error of a second-order method).
TEST(BeamDynamicsAdaptive, LocalErrorEstimateTracksTheOneStepError) {
  /// The estimate's third derivative is a difference quotient of a lagged acceleration: a
  /// factor of 2 either way is what an estimate for step-size control needs.
  constexpr double kMaxRatio = 2.0;
  /// Observed orders seen: 2.6 to 3.2 (the fixed-step history before the step differs per dt).
  constexpr double kOrderTolerance = 0.5;
  for (const double rho_inf : {0.0, 0.9}) {
    SCOPED_TRACE(rho_inf);
    std::vector<double> h, est, act;
    for (const double dt : {2e-4, 1e-4, 5e-5}) {
      const OneStep s = one_step_error(dt, rho_inf);
      std::printf("rho_inf %.1f, dt %.1e: estimate %.3e m, actual %.3e m, ratio %.3f\n", rho_inf,
                  dt, s.estimate, s.actual, s.estimate / s.actual);
      EXPECT_GT(s.estimate, s.actual / kMaxRatio);
      EXPECT_LT(s.estimate, s.actual * kMaxRatio);
      h.push_back(dt);
      est.push_back(s.estimate);
      act.push_back(s.actual);
    }
    test_support::ExpectOrderInBracket(h, est, 3.0, kOrderTolerance);
    test_support::ExpectOrderInBracket(h, act, 3.0, kOrderTolerance);
  }
}

// undo_step returns every part of the state bit for bit (Kelvin-Voigt history, strings), also
// after a failed step; a repeated step converges to the same state within the tolerance.
TEST(BeamDynamicsAdaptive, UndoStepReturnsToTheStateBeforeTheStep) {
  const rod::RodModel m = test_support::steel_cantilever_with_strings();
  DynamicsOptions o;
  o.elements = 4;
  o.dt_s = 1e-3;
  o.viscosity_Pa_s = 1e7;
  BeamDynamics d(m, o);
  ASSERT_TRUE(d.initialize(sag(m, 0.02)).converged());
  d.undo_step();  // a no-op before any step
  const rod::Loads released = sag(m, 0.0);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(d.step(released).converged());
  const State s0 = d.state();
  const Eigen::VectorXd v0 = d.velocities();
  const double t0 = d.time_s(), e0 = d.local_error_m(), E0 = d.kinetic_energy_J();
  ASSERT_TRUE(d.step(released).converged());
  const Eigen::Vector3d tip1 = d.tip_position_W_m();
  d.undo_step();
  EXPECT_EQ(d.time_s(), t0);
  EXPECT_EQ(d.local_error_m(), e0);
  EXPECT_EQ(d.kinetic_energy_J(), E0);
  EXPECT_TRUE(d.velocities() == v0);
  for (std::size_t k = 0; k < s0.p_W_m.size(); ++k) {
    EXPECT_TRUE(d.state().p_W_m[k] == s0.p_W_m[k]) << k;
    EXPECT_TRUE(d.state().q_WB[k].coeffs() == s0.q_WB[k].coeffs()) << k;
  }
  EXPECT_TRUE(d.state().tensions_N == s0.tensions_N);
  // The same step again lands where it did (the Newton iterates may differ: the factorization
  // kept is the later one).
  ASSERT_TRUE(d.step(released).converged());
  EXPECT_LT((d.tip_position_W_m() - tip1).norm(), 1e-9);
  // A failed step (one Newton iteration allowed) is undone the same way.
  d.undo_step();
  DynamicsOptions o1 = o;
  o1.max_iterations = 1;
  BeamDynamics f(m, o1);
  ASSERT_TRUE(f.initialize(sag(m, 0.02)).converged());
  const State f0 = f.state();
  ASSERT_FALSE(f.step(released).converged());
  f.undo_step();
  EXPECT_EQ(f.time_s(), 0.0);
  for (std::size_t k = 0; k < f0.p_W_m.size(); ++k) EXPECT_TRUE(f.state().p_W_m[k] == f0.p_W_m[k]);
}

// set_time_step with the step in use changes nothing: a run that sets it before every step is
// bit-identical to one that never does. A new size is checked by name.
TEST(BeamDynamicsAdaptive, ConstantStepsAreBitIdenticalWithSetTimeStep) {
  const rod::RodModel m = test_support::steel_cantilever_till();
  DynamicsOptions o;
  o.elements = 6;
  o.dt_s = 2e-3;
  o.viscosity_Pa_s = 2e7;
  BeamDynamics a(m, o), b(m, o);
  ASSERT_TRUE(a.initialize(sag(m, 0.02)).converged());
  ASSERT_TRUE(b.initialize(sag(m, 0.02)).converged());
  const rod::Loads released = sag(m, 0.0);
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(a.step(released).converged());
    b.set_time_step(2e-3);
    ASSERT_TRUE(b.step(released).converged());
  }
  EXPECT_TRUE(a.velocities() == b.velocities());
  EXPECT_TRUE(a.tip_position_W_m() == b.tip_position_W_m());
  EXPECT_EQ(a.error_order(), 2);
  EXPECT_GT(a.local_error_m(), 0.0);
  EXPECT_THROW(a.set_time_step(0.0), InputError);
  EXPECT_THROW(a.set_time_step(std::nan("")), InputError);
}

// After a change of step size the run stays second order: alternating steps dt and dt/2
// converge at order 2 to the fine run's tip.
TEST(BeamDynamicsAdaptive, VaryingStepsStaySecondOrder) {
  const rod::RodModel m = test_support::steel_cantilever_till();
  const auto tip_at = [&](double dt) {
    DynamicsOptions o;
    o.elements = 6;
    o.dt_s = dt;
    BeamDynamics d(m, o);
    EXPECT_TRUE(d.initialize(rod::Loads::from_model(m)).converged());
    // Pairs of steps 4/3 dt and 2/3 dt (sum 2 dt) up to 0.024 s.
    const int pairs = static_cast<int>(std::lround(0.024 / (2.0 * dt)));
    double t = 0.0;
    for (int k = 0; k < pairs; ++k) {
      for (const double h : {4.0 / 3.0 * dt, 2.0 / 3.0 * dt}) {
        d.set_time_step(h);
        t += h;
        EXPECT_TRUE(d.step(smooth_loads(m, t)).converged());
      }
    }
    return d.tip_position_W_m();
  };
  const Eigen::Vector3d ref = tip_at(2.5e-5);
  std::vector<double> h, err;
  for (const double dt : {8e-4, 4e-4, 2e-4, 1e-4}) {
    h.push_back(dt);
    err.push_back((tip_at(dt) - ref).norm());
  }
  std::printf("%s", test_support::convergence_table(h, err).c_str());
  // From the second pair: the coarsest level is pre-asymptotic (order 2.6 seen).
  test_support::ExpectOrderInBracket(h, err, 2.0, 0.4, 1);
}

}  // namespace
}  // namespace tcasim::beam_fe
