// Tip constraint of the shooting solver (blocked tip): pinned and normal-only holders.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Vector3d;
using units::degC_to_K;

/// The constrained and free solves are converged to a scaled residual of 1e-12.
constexpr double kSolverTolerance = 1e-12;
/// Tip position error of a converged constrained solve: the residual (p - p*)/L <= 1e-12.
constexpr double kHeldPosition_m = 1e-12 * 0.040 * 10.0;
/// A free solve loaded by the reaction reproduces the held tip to the solve tolerances
/// (both problems share the discrete RK4 map): residual 1e-12 x compliance ~ 1e-13 m.
constexpr double kReproducedPosition_m = 1e-10;
/// Global equilibrium: RK4 with 400 steps integrates the loads to ~1e-12 of F_c (~0.02 N);
/// a reaction left out of the balance would show as its full size (~1e-3 N).
constexpr double kImbalance_N = 1e-12;
/// The held rod's reaction equals the load that bent it, to the solve tolerance x F_c.
constexpr double kReactionAsLoad_N = 1e-11;
/// Reaction at the free tip: the solve residual 1e-12 x F_c (~0.02 N) plus round-off.
constexpr double kZeroReaction_N = 1e-11;
/// Jacobian check: central differences are accurate to ~1e-9 of the entries.
constexpr double kJacobianRelative = 1e-6;

Options rk4(int steps) {
  Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = kSolverTolerance;
  return o;
}

/// Square manipulator at 100 degC and the tip position the free body reaches at 60 degC.
struct Held {
  rod::RodModel model;
  Vector3d free_tip_hot, target;
};

Held square_held_at_60degC() {
  Held h;
  h.model = testing::square_manipulator(degC_to_K(100.0));
  rod::RodModel cool = testing::square_manipulator(degC_to_K(60.0));
  const rod::Result rc = solve(cool, rk4(64));
  const rod::Result rh = solve(h.model, rk4(64));
  EXPECT_TRUE(rc.converged && rh.converged);
  h.target = rc.tip_position_W_m;
  h.free_tip_hot = rh.tip_position_W_m;
  return h;
}

TEST(TipConstraint, PinnedTipIsHeldAndReactionBalancesGlobalEquilibrium) {
  Held h = square_held_at_60degC();
  h.model.tip_constraint = rod::TipConstraint{h.target, std::nullopt};
  ShootingSolver solver(h.model, rk4(400));
  EXPECT_EQ(solver.unknown_count(), 6 + 1 + 3);
  const rod::Loads act = rod::Loads::from_model(h.model);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result r = solver.make_result(act, sol, s);
  ASSERT_TRUE(r.tip_reaction_force_W_N.has_value());
  EXPECT_LE((r.tip_position_W_m - h.target).norm(), kHeldPosition_m);
  // Held less bent than it wants to be: the holder pushes the tip back toward +x (the
  // heated TCA at +x bends the body toward -x).
  EXPECT_GT(r.tip_reaction_force_W_N->x(), 0.0);
  // The global balance includes the reaction as a tip load.
  EXPECT_LE(s.force_imbalance_W_N.norm(), kImbalance_N);
  EXPECT_LE(s.moment_imbalance_W_Nm.norm(), kImbalance_N * h.model.length_m);
}

TEST(TipConstraint, PinnedReactionAppliedAsTipLoadReproducesHeldPosition) {
  Held h = square_held_at_60degC();
  h.model.tip_constraint = rod::TipConstraint{h.target, std::nullopt};
  ShootingSolver solver(h.model, rk4(64));
  const rod::Loads act = rod::Loads::from_model(h.model);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const Vector3d reaction = *solver.make_result(act, sol, s).tip_reaction_force_W_N;

  rod::RodModel free = h.model;
  free.tip_constraint.reset();
  free.tip_force_W_N = reaction;
  const rod::Result rf = solve(free, rk4(64));
  ASSERT_TRUE(rf.converged) << rf.message;
  EXPECT_LE((rf.tip_position_W_m - h.target).norm(), kReproducedPosition_m);
  EXPECT_FALSE(rf.tip_reaction_force_W_N.has_value());
}

TEST(TipConstraint, PinnedAtTheFreeTipGivesZeroReaction) {
  Held h = square_held_at_60degC();
  h.model.tip_constraint = rod::TipConstraint{h.free_tip_hot, std::nullopt};
  const rod::Result r = solve(h.model, rk4(64));
  ASSERT_TRUE(r.converged) << r.message;
  // The free tip (same discretization) is where the rod rests: no force needed.
  EXPECT_LE(r.tip_reaction_force_W_N->norm(), kZeroReaction_N);
}

TEST(TipConstraint, NormalOnlyHoldsTheNormalComponentWithAForceAlongTheNormal) {
  Held h = square_held_at_60degC();
  const Vector3d n = Vector3d(-1.0, 0.0, 0.2).normalized();
  h.model.tip_constraint = rod::TipConstraint{h.target, n};
  ShootingSolver solver(h.model, rk4(400));
  EXPECT_EQ(solver.unknown_count(), 6 + 1 + 1);
  const rod::Loads act = rod::Loads::from_model(h.model);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result r = solver.make_result(act, sol, s);
  const Vector3d F = *r.tip_reaction_force_W_N;
  EXPECT_NEAR(n.dot(r.tip_position_W_m - h.target), 0.0, kHeldPosition_m);
  EXPECT_LE((F - n.dot(F) * n).norm(), 1e-15);              // along the normal only
  EXPECT_LT(n.dot(F), 0.0);                                 // the holder pushes against the bending
  EXPECT_GT((r.tip_position_W_m - h.target).norm(), 1e-6);  // tangentially free
  EXPECT_LE(s.force_imbalance_W_N.norm(), kImbalance_N);
  // As a tip load on the free rod it reproduces the constrained tip.
  rod::RodModel free = h.model;
  free.tip_constraint.reset();
  free.tip_force_W_N = F;
  const rod::Result rf = solve(free, rk4(400));
  ASSERT_TRUE(rf.converged);
  EXPECT_LE((rf.tip_position_W_m - r.tip_position_W_m).norm(), kReproducedPosition_m);
}

TEST(TipConstraint, SensitivityJacobianOfConstrainedResidualMatchesCentralDifferences) {
  for (bool normal_only : {false, true}) {
    Held h = square_held_at_60degC();
    h.model.tip_constraint = rod::TipConstraint{h.target, std::nullopt};
    if (normal_only) h.model.tip_constraint->normal_W = Vector3d(-1.0, 0.0, 0.0);
    Options os = rk4(32), oc = rk4(32);
    oc.jacobian = JacobianMethod::kCentralDifference;
    ShootingSolver ss(h.model, os), sc(h.model, oc);
    const rod::Loads act = rod::Loads::from_model(h.model);
    Solution sol;
    ASSERT_TRUE(ss.solve(act, sol).converged());
    Eigen::VectorXd x = sol.unknowns;
    x.tail(normal_only ? 1 : 3).array() += 1e-3;  // off the solution: reaction terms matter
    Eigen::MatrixXd Js, Jc;
    ASSERT_TRUE(ss.jacobian(act, x, Js));
    ASSERT_TRUE(sc.jacobian(act, x, Jc));
    EXPECT_LE((Js - Jc).norm(), kJacobianRelative * Jc.norm())
        << (normal_only ? "normal" : "pinned");
  }
}

TEST(TipConstraint, HeldWhereATipLoadPutsTheTipTheReactionIsThatLoad) {
  // A cold, passive rod without gravity bent by a known tip load; held at that tip
  // position without the load, the holder supplies the same force.
  rod::RodModel loaded = testing::square_manipulator(degC_to_K(25.0));
  loaded.gravity_W_m_s2.setZero();
  loaded.tip_force_W_N = {-0.004, 0.001, -0.002};
  const rod::Result rl = solve(loaded, rk4(64));
  ASSERT_TRUE(rl.converged) << rl.message;
  rod::RodModel held = loaded;
  held.tip_force_W_N.setZero();
  held.tip_constraint = rod::TipConstraint{rl.tip_position_W_m, std::nullopt};
  const rod::Result r = solve(held, rk4(64));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE((*r.tip_reaction_force_W_N - loaded.tip_force_W_N).norm(), kReactionAsLoad_N);
}

}  // namespace
}  // namespace tcasim::cosserat
