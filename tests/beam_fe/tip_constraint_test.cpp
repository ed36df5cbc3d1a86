// Blocked tip (scenario key tip_constraint): pinned tip and normal-only contact solved with
// Lagrange multipliers. The reaction is the force the holder applies TO the rod (world frame).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "beam_fe/beam_fe.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "models.hpp"
#include "support/convergence.hpp"

namespace tcasim::beam_fe {
namespace {

using testing::options;
using testing::run;
using testing::Solved;

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Stress-free tip of a model (exact arc of omega* from the clamp).
Vector3d reference_tip(const rod::RodModel& m) {
  const Vector3d phi = m.length_m * m.reference_curvature_at(0.0);
  return m.base_position_W_m + m.R_WB0 * (m.length_m * so3::left_jacobian(phi) * Vector3d::UnitZ());
}

/// The paper's circular manipulator at 90 degC (heated extension TCA: pushes, bends toward
/// -x; its free tip is near (-24.0, 0, 30.2) mm) with its tip held at `position_m`.
rod::RodModel held_manipulator(const Vector3d& position_m,
                               const std::optional<Vector3d>& normal = {}) {
  rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  rod::TipConstraint c;
  c.position_W_m = position_m;
  if (normal) c.normal_W = normal->normalized();
  m.tip_constraint = c;
  return m;
}

/// A converged residual row is within ~1e-12 of the load scale (plus round-off ~1e-12 N);
/// sums over the ~2n nodes of a mesh stay below 1e-8 of the load scale.
constexpr double kBalance = 1e-8;

/// A held point 2 mm short of the free tip's bending, 1 mm out of plane: the holder pushes
/// back against the TCA without compressing the soft rod past its buckling load (a held point
/// far inside the free tip needs compressive tip forces several times the Euler load, whose
/// dead-load equilibrium is not unique).
const Vector3d kHeldPoint_m(-0.022, 0.001, 0.031);

/// Clamp reaction (force and moment on the rod, world frame): the first element's internal
/// nodal forces at the base node (they include the strings' base terminations) minus the
/// share of the weight the clamp takes directly (int N_0 w ds = w h/6 for a quadratic element).
void clamp_reaction(const rod::RodModel& m, const Discretization& disc, const State& st,
                    Vector3d& force, Vector3d& moment) {
  const ElementEvaluation ev = disc.element(st, 0, st.tensions_N);
  const double h = m.length_m / disc.element_count();
  force = ev.residual.head<3>() - h / 6.0 * m.weight_per_length_W_N_m();
  moment = st.q_WB[0].toRotationMatrix() * ev.residual.segment<3>(3);
}

/// Force and moment (about the world origin) of the weight, by Simpson's rule on each
/// quadratic element (nodes at 0, h/2, h): quadrature error ~h^4, far below kBalance on 32+.
void weight_resultant(const rod::RodModel& m, const State& st, Vector3d& force, Vector3d& moment) {
  const Vector3d w = m.weight_per_length_W_N_m();
  force = m.length_m * w;
  moment.setZero();
  const double h = m.length_m / ((st.p_W_m.size() - 1) / 2);
  for (std::size_t k = 0; k + 2 < st.p_W_m.size(); k += 2) {
    moment += h / 6.0 * (st.p_W_m[k] + 4.0 * st.p_W_m[k + 1] + st.p_W_m[k + 2]).cross(w);
  }
}

void expect_global_equilibrium(const rod::RodModel& m, const Options& opt, const State& st) {
  const Discretization disc(m, opt);
  Vector3d F0, M0, Fw, Mw;
  clamp_reaction(m, disc, st, F0, M0);
  weight_resultant(m, st, Fw, Mw);
  const Vector3d Fh = st.tip_reaction_W_N;
  const Vector3d p0 = st.p_W_m.front(), pL = st.p_W_m.back();
  const double scale = std::max({Fw.norm(), Fh.norm(), F0.norm()});
  // [conventions.md] global equilibrium: clamp, weight, tip wrench and holder balance.
  const Vector3d force = F0 + Fw + m.tip_force_W_N + Fh;
  const Vector3d moment =
      M0 + p0.cross(F0) + Mw + pL.cross(m.tip_force_W_N + Fh) + m.tip_moment_W_Nm;
  std::printf(
      "clamp force (%.6e, %.6e, %.6e) N, holder (%.6e, %.6e, %.6e) N, imbalance %.2e N, %.2e N m\n",
      F0.x(), F0.y(), F0.z(), Fh.x(), Fh.y(), Fh.z(), force.norm(), moment.norm());
  EXPECT_LT(force.norm(), kBalance * scale);
  EXPECT_LT(moment.norm(), kBalance * scale * m.length_m);
}

TEST(BeamFeTipConstraint, PinnedTipWithTcaHoldsThePointAndBalancesGlobalForcesAndMoments) {
  const rod::RodModel m = held_manipulator(kHeldPoint_m);
  const Options opt = options(32);
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  // Constraint rows k_c |gap| <= 1e-12 N-ish with k_c = EA/L ~ 50 N/m: gap ~ 1e-13 m.
  constexpr double kHeld = 1e-10;
  EXPECT_LT((s.state.p_W_m.back() - m.tip_constraint->position_W_m).norm(), kHeld * m.length_m);
  EXPECT_GT(s.state.tip_reaction_W_N.norm(), 1e-4);  // the holder does work against the TCA
  expect_global_equilibrium(m, opt, s.state);
  const rod::Result res = make_result(m, opt, s.state, s.summary);
  ASSERT_TRUE(res.tip_reaction_force_W_N.has_value());
  EXPECT_EQ(*res.tip_reaction_force_W_N, s.state.tip_reaction_W_N);
}

TEST(BeamFeTipConstraint, ReactionAppliedAsATipForceReproducesTheHeldPosition) {
  const rod::RodModel held = held_manipulator(kHeldPoint_m);
  const Options opt = options(16);
  const Solved a = run(held, opt);
  ASSERT_TRUE(a.summary.converged()) << a.summary.message;
  rod::RodModel free = held;
  free.tip_constraint.reset();
  free.tip_force_W_N = a.state.tip_reaction_W_N;
  const Solved b = run(free, opt);
  ASSERT_TRUE(b.summary.converged()) << b.summary.message;
  // Both solves converged to ~1e-12 N on a compliance ~3 m/N (EcoFlex cantilever L^3/3EI):
  // positions agree to ~1e-11 m.
  constexpr double kSolverTolerance = 1e-9;
  EXPECT_LT((b.state.p_W_m.back() - held.tip_constraint->position_W_m).norm(),
            kSolverTolerance * held.length_m);
  EXPECT_NEAR(b.state.tensions_N[0], a.state.tensions_N[0],
              kSolverTolerance * std::abs(a.state.tensions_N[0]));
  EXPECT_FALSE(make_result(free, opt, b.state, b.summary).tip_reaction_force_W_N.has_value());
}

TEST(BeamFeTipConstraint, NormalOnlyContactPushesAlongTheNormalAndLeavesTheTangentialMotionFree) {
  // The heated TCA bends the rod toward -x; a tilted wall 2 mm in from the free tip stops it.
  const Options opt = options(32);
  rod::RodModel free = testing::circular_manipulator(units::degC_to_K(90.0));
  const Solved f = run(free, opt);
  ASSERT_TRUE(f.summary.converged()) << f.summary.message;
  const Vector3d n = Vector3d(1.0, 0.2, 0.1).normalized();
  const Vector3d wall = f.state.p_W_m.back() + 0.002 * n;
  const rod::RodModel m = held_manipulator(wall, n);
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const Vector3d F = s.state.tip_reaction_W_N;
  EXPECT_GT(F.dot(n), 0.0);                        // the wall pushes
  EXPECT_LT(F.cross(n).norm(), 1e-14 * F.norm());  // along its normal (round-off)
  constexpr double kHeld = 1e-10;
  EXPECT_NEAR(n.dot(s.state.p_W_m.back() - m.tip_constraint->position_W_m), 0.0,
              kHeld * m.length_m);
  // The tangential position is not held: it differs from the wall point by millimetres.
  const Vector3d slip = s.state.p_W_m.back() - m.tip_constraint->position_W_m;
  EXPECT_GT((slip - n.dot(slip) * n).norm(), 1e-4);
  expect_global_equilibrium(m, opt, s.state);
}

TEST(BeamFeTipConstraint, ConstraintAtTheReferenceTipGivesZeroReactionWithoutActuation) {
  // Straight rod on a rotated, moved clamp; a string with zero tension; no gravity. (A
  // precurved reference is not used: its nodes lie on the exact arc, which the quadratic
  // position interpolation reproduces only to O(h^3), so the discrete rod is stressed at
  // ~1e-8 of its stiffness and the reaction is that discretization error, not zero.)
  rod::RodModel m = testing::stiffness_rod(0.5, 60.0, 25.0, 0.02, 0.03, 0.015);
  m.R_WB0 = so3::exp(Vector3d(0.3, -0.7, 0.2));
  m.base_position_W_m = {0.1, 0.2, -0.3};
  testing::add_tension_string(m, "idle", 0.01, 0.0, 0.0);
  for (const bool normal_only : {false, true}) {
    SCOPED_TRACE(normal_only ? "normal-only" : "pinned");
    rod::RodModel held = m;
    rod::TipConstraint c;
    c.position_W_m = reference_tip(m);
    if (normal_only) c.normal_W = Vector3d(0.0, 0.6, 0.8);
    held.tip_constraint = c;
    const Solved s = run(held, options(8));
    ASSERT_TRUE(s.summary.converged()) << s.summary.message;
    // Stiffness ~60 N times round-off of strains ~1e-15: reactions ~1e-13 N at most.
    constexpr double kRoundOffForce = 1e-12;
    EXPECT_LT(s.state.tip_reaction_W_N.norm(), kRoundOffForce);
    EXPECT_LT((s.state.p_W_m.back() - c.position_W_m).norm(), 1e-14);
  }
}

TEST(BeamFeTipConstraint, ReactionForceConvergesAtOrderFourWithQuadraticElements) {
  const rod::RodModel m = held_manipulator(kHeldPoint_m);
  const Solved ref = run(m, options(128));
  ASSERT_TRUE(ref.summary.converged()) << ref.summary.message;
  const std::vector<int> meshes{4, 8, 16, 32};
  std::vector<double> h, e;
  for (const int n : meshes) {
    const Solved s = run(m, options(n));
    ASSERT_TRUE(s.summary.converged()) << s.summary.message;
    h.push_back(m.length_m / n);
    e.push_back((s.state.tip_reaction_W_N - ref.state.tip_reaction_W_N).norm());
  }
  std::printf("pinned manipulator, reaction force, quadratic:\n%s",
              test_support::convergence_table(h, e).c_str());
  // The same bracket as the tip-position gates of solver_test.cpp.
  constexpr double kQuadraticOrder = 4.0, kQuadraticBracket = 0.3;
  test_support::ExpectOrderInBracket(h, e, kQuadraticOrder, kQuadraticBracket);
}

}  // namespace
}  // namespace tcasim::beam_fe
