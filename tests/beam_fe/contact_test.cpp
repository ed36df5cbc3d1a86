// Frictionless contact of the FE mesh nodes with rigid obstacles (primal-dual active set):
// closed forms of a heavy rod on a floor and of a propped cantilever, the clamp reaction and
// the global balance, a warm-started sweep across contact onset, a rectangular section's
// corner on a plane, and the contact tangent against central differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dynamics.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "models.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::options;

constexpr double kSteelE_Pa = 210e9, kSteelPoisson = 0.3, kSteelDensity = 7850.0;
constexpr double kG = 9.81;

/// A steel rod of length 1 m and diameter d clamped horizontally along world x with its
/// centerline at height z0 (body e1 = world y, e2 = world z, e3 = world x).
rod::RodModel horizontal_rod(double diameter_m, double z0_m) {
  rod::RodModel m =
      testing::circular_rod(1.0, diameter_m, kSteelE_Pa, kSteelPoisson, kSteelDensity);
  m.name = "horizontal-rod";
  m.R_WB0 << 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  m.base_position_W_m = Vector3d(0.0, 0.0, z0_m);
  return m;
}

/// Global balance of a solve (docs/conventions.md "Contact in the FE"): clamp reaction +
/// weight + tip force (with the tip mass's weight) + contact forces = 0, and the same for
/// moments about the base point, tip moment included. The nodal weights are the consistent
/// nodal loads, whose moment is exactly that of the interpolated centerline's weight. In exact
/// arithmetic the imbalance is minus the sum of the free nodes' residual rows (the internal
/// forces of every element are balanced: objective strains), so the check is |imbalance| <=
/// sum of |r| over those rows (mapped to world moments about the base) plus round-off of the
/// sums (64 eps of the largest term times the number of terms).
void expect_global_balance(const rod::RodModel& m, const Solver& solver, const rod::Result& res,
                           const State& st, const rod::Loads& loads) {
  const Discretization& disc = solver.discretization();
  const LoadCase lc = disc.load_case(loads);
  ASSERT_TRUE(res.base_reaction.has_value());
  const Vector3d p0 = m.base_position_W_m;
  Vector3d force = res.base_reaction->force_W_N, moment = res.base_reaction->moment_W_Nm;
  double largest = std::max(force.norm(), moment.norm() / m.length_m);
  const Vector3d g = lc.loads.gravity_W_m_s2;
  for (int k = 0; k < disc.node_count(); ++k) {
    const Vector3d w = disc.node_mass_kg()[k] * g;
    force += w;
    moment += (st.p_W_m[k] - p0).cross(w);
    largest = std::max(largest, w.norm());
  }
  const Vector3d tip = lc.loads.tip_force_W_N + m.tip_mass_kg * g;
  force += tip;
  moment += (st.p_W_m.back() - p0).cross(tip) + lc.loads.tip_moment_W_Nm;
  for (const rod::ContactResult& c : res.contacts) {
    force += c.force_W_N;
    moment += c.moment_W_Nm;
    largest = std::max(largest, c.force_W_N.norm());
  }
  largest = std::max(largest, tip.norm());
  const VectorXd r = disc.residual(st, lc, 1.0);
  double r_force = 0.0, r_moment = 0.0;
  for (int k = 1; k < disc.node_count(); ++k) {
    const Vector3d f = r.segment<3>(6 * (k - 1));
    r_force += f.norm();
    r_moment += (st.p_W_m[k] - p0).norm() * f.norm() + r.segment<3>(6 * (k - 1) + 3).norm();
  }
  const double round_off =
      64.0 * std::numeric_limits<double>::epsilon() * largest * (disc.node_count() + 4);
  std::printf(
      "  balance: clamp (%.6e, %.6e, %.6e) N, imbalance %.2e N (bound %.2e), %.2e N m "
      "(bound %.2e)\n",
      res.base_reaction->force_W_N.x(), res.base_reaction->force_W_N.y(),
      res.base_reaction->force_W_N.z(), force.norm(), r_force + round_off, moment.norm(),
      r_moment + round_off * m.length_m);
  EXPECT_LE(force.norm(), r_force + round_off);
  EXPECT_LE(moment.norm(), r_moment + round_off * m.length_m);
}

/// Solves with a fresh state; the solve's wall time into *seconds.
struct ContactRun {
  Summary summary;
  State state;
  rod::Result result;
};
ContactRun solve_model(const rod::RodModel& m, const Options& opt) {
  ContactRun out;
  const Solver solver(m, opt);
  const rod::Loads loads = rod::Loads::from_model(m);
  out.summary = solver.solve(loads, out.state);
  out.result = solver.make_result(loads, out.state, out.summary);
  return out;
}

// --- (a) A heavy rod clamped horizontally above a floor ---------------------------------------

/// Small-slope closed form (Euler-Bernoulli, rigid frictionless floor): free span l =
/// (72 B H / q)^(1/4), touchdown force q l / 3, clamp force 2 q l / 3 up and clamp moment q l^2
/// / 6 (holding the span up); beyond l the rod lies flat and carries its weight q. Its largest
/// slope is 2 q l^3 / (81 B) = 16 H / (9 l) (at 2 l / 3 from the touchdown).
struct HeavyRodOnFloor {
  double free_span_m, clamp_force_N, clamp_moment_Nm, max_slope;
};
HeavyRodOnFloor heavy_rod_closed_form(double B, double q, double H) {
  const double l = std::pow(72.0 * B * H / q, 0.25);
  return {l, 2.0 * q * l / 3.0, q * l * l / 6.0, 16.0 * H / (9.0 * l)};
}

struct FloorErrors {
  double force, moment;  // relative errors of the clamp force and moment
  double span_m;         // first node in contact minus l
  double allowed;        // the physical error bound (heavy_rod_errors)
  int iterations;
};

/// The heavy steel rod (d = 2 mm) at clearance H above the floor on `elements` quadratic
/// elements, from the straight rod in one solve.
FloorErrors heavy_rod_errors(double H, int elements) {
  const double d = 2e-3;
  rod::RodModel m = horizontal_rod(d, H + 0.5 * d);
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles = {testing::plane_obstacle()};
  const Options opt = options(elements);
  const Solver solver(m, opt);
  State st;
  const rod::Loads loads = rod::Loads::from_model(m);
  const Summary sum = solver.solve(loads, st);
  EXPECT_TRUE(sum.converged()) << sum.message;
  const rod::Result res = solver.make_result(loads, st, sum);
  const Discretization& disc = solver.discretization();
  const double B = m.bending_torsion_stiffness()[0];
  const double q = -m.weight_per_length_W_N_m().z();
  const HeavyRodOnFloor cf = heavy_rod_closed_form(B, q, H);
  double s_first = m.length_m;  // first node in contact
  for (const rod::ContactSample& smp : disc.contact_samples(st, 0))
    if (smp.force_W_N.z() > 0.0) s_first = std::min(s_first, smp.s_m);
  FloorErrors e;
  e.force = res.base_reaction->force_W_N.z() / cf.clamp_force_N - 1.0;
  e.moment = -res.base_reaction->moment_W_Nm.y() / cf.clamp_moment_Nm - 1.0;
  e.span_m = s_first - cf.free_span_m;
  e.iterations = sum.iterations;
  // Error bound: the small-slope theory's neglected terms, relative max_slope^2; the mesh's,
  // (element length / l)^2 (measured far below it, see the convergence test); and the solve's
  // own: its residual rows (round-off of a steel rod's strains, ~eps nodes EA) summed over the
  // nodes, relative to the span's weight q l.
  const double h = m.length_m / disc.element_count();
  e.allowed = cf.max_slope * cf.max_slope + std::pow(h / cf.free_span_m, 2) +
              disc.node_count() * sum.residual_inf / (q * cf.free_span_m);
  std::printf(
      "  H %.1e m, %3d elements: l %.4f m, clamp force err %+.3e, moment err %+.3e "
      "(bound %.1e), first contact node - l = %+.2e m, %d iterations, %d load step(s), "
      "%.3f s\n",
      H, elements, cf.free_span_m, e.force, e.moment, e.allowed, e.span_m, sum.iterations,
      sum.load_steps, sum.wall_time_s);
  EXPECT_LT(std::abs(e.force), e.allowed);
  EXPECT_LT(std::abs(e.moment), e.allowed);
  // Node-only contact: the first node in contact lies within a node spacing (h / 2) of the
  // touchdown, one more for a node at the touchdown whose force is at round-off level.
  EXPECT_LT(std::abs(e.span_m), h);
  expect_global_balance(m, solver, res, st, loads);
  return e;
}

TEST(BeamFeContact, HeavyRodOnAFloorConvergesToTheSmallSlopeClosedForm) {
  // Mesh refinement at H = 1 mm (free span 0.47 m, slope <= 3.8e-3: small-slope error ~1e-5).
  std::printf("mesh refinement (H = 1 mm):\n");
  std::vector<FloorErrors> mesh;
  const std::vector<int> elements = {16, 32, 64, 128};
  for (const int n : elements) mesh.push_back(heavy_rod_errors(1e-3, n));
  for (std::size_t i = 1; i < mesh.size(); ++i) {
    std::printf("  observed order %d -> %d elements: clamp force %.2f, moment %.2f\n",
                elements[i - 1], elements[i],
                std::log2(std::abs(mesh[i - 1].force) / std::abs(mesh[i].force)),
                std::log2(std::abs(mesh[i - 1].moment) / std::abs(mesh[i].moment)));
  }
  EXPECT_LT(std::abs(mesh.back().force), std::abs(mesh[1].force));
  EXPECT_LT(std::abs(mesh.back().moment), std::abs(mesh[1].moment));
  // Clearance: the small-slope error ~max_slope^2 ~ (H / l)^2 shrinks with H until the mesh
  // and round-off errors (~1e-5 here) take over.
  std::printf("clearance (128 elements):\n");
  std::vector<FloorErrors> clearance;
  for (const double H : {16e-3, 8e-3, 4e-3}) clearance.push_back(heavy_rod_errors(H, 128));
  EXPECT_LT(std::abs(clearance[1].force), std::abs(clearance[0].force));
  EXPECT_LT(std::abs(clearance[2].force), std::abs(clearance[1].force));
}

// --- (b) Propped cantilever ---------------------------------------------------------------------

/// The small-deflection support reaction of a cantilever with tip load P on a support at x = a,
/// with shear flexibility 1/S (Timoshenko; S -> inf gives P (3 L - a) / (2 a)): the support
/// cancels the deflection at a of the tip load, P a^2 (3 L - a) / (6 B) + P a / S, with its
/// own R a^3 / (3 B) + R a / S.
double propped_reaction(double P, double L, double a, double B, double S) {
  return (P * a * a * (3.0 * L - a) / (6.0 * B) + P * a / S) / (a * a * a / (3.0 * B) + a / S);
}

TEST(BeamFeContact, ProppedCantileverOnASphereMatchesTheSmallDeflectionReaction) {
  // A stout steel rod (d = 10 mm, L = 1 m) so that the small deflection (tip slope 1e-3,
  // geometric error ~1e-6) stays far above the residual's round-off (~eps nodes EA).
  const double d = 10e-3, r = 0.5 * d, R_s = 5e-3, theta = 1e-3;
  for (const double a : {0.5, 0.75}) {
    SCOPED_TRACE("a = " + std::to_string(a));
    rod::RodModel m = horizontal_rod(d, 0.0);
    rod::Obstacle support;
    support.name = "support";
    support.type = rod::Obstacle::Type::kSphere;
    support.radius_m = R_s;
    support.point_W_m = Vector3d(a, 0.0, -r - R_s);  // touches the rod's underside at x = a
    m.obstacles = {support};
    const double B = m.bending_torsion_stiffness()[0];
    const double S = m.shear_extension_stiffness()[1];
    const double P = 2.0 * B * theta / (m.length_m * m.length_m);
    m.tip_force_W_N = Vector3d(0.0, 0.0, -P);
    const Options opt = options(32);  // nodes every 1/64 m: a is a node
    const ContactRun run = solve_model(m, opt);
    ASSERT_TRUE(run.summary.converged()) << run.summary.message;
    ASSERT_EQ(run.result.contacts.size(), 1u);
    const rod::ContactResult& c = run.result.contacts[0];
    ASSERT_EQ(c.regions.size(), 1u);
    EXPECT_EQ(c.regions[0].s0_m, a);  // one node: a point contact
    EXPECT_EQ(c.regions[0].s1_m, a);
    const double expected = propped_reaction(P, m.length_m, a, B, S);
    // Geometric nonlinearity ~theta^2 = 1e-6, the mesh (exact cubic deflections between the
    // loaded nodes up to the shear-locking-free element's ~(h/L)^2 (r/L)^2 ~ 1e-8) and the
    // round-off of the residual rows (a few eps nodes EA ~ 2e-6 N, 1e-6 of R): 1e-5.
    constexpr double kPropped = 1e-5;
    std::printf(
        "  a = %.2f: reaction %.9e N, closed form %.9e N (Euler-Bernoulli %.9e), rel. "
        "err %+.2e, %d iterations\n",
        a, c.force_W_N.z(), expected, P * (3.0 * m.length_m - a) / (2.0 * a),
        c.force_W_N.z() / expected - 1.0, run.summary.iterations);
    EXPECT_NEAR(c.force_W_N.z(), expected, kPropped * expected);
    EXPECT_LT(std::abs(c.force_W_N.x()) + std::abs(c.force_W_N.y()), kPropped * expected);
    const Solver solver(m, opt);
    expect_global_balance(m, solver, run.result, run.state, rod::Loads::from_model(m));
  }
}

// A small sphere under the rod between two nodes: the nodes pass on either side of it, so the
// contact solve converges without touching it. The result says so (its status), and a mesh
// whose nodes resolve the sphere holds the rod on it.
TEST(BeamFeContact, ASphereBetweenTwoNodesIsReportedAndResolvedByRefinement) {
  const double d = 2e-3, R_s = 4e-3;
  rod::RodModel m = horizontal_rod(d, 0.0);
  rod::Obstacle ball;
  ball.name = "ball";
  ball.type = rod::Obstacle::Type::kSphere;
  ball.radius_m = R_s;
  // Between the nodes at 0.5 and 0.53125 of 16 quadratic elements, 1 mm below the surface.
  ball.point_W_m = Vector3d(0.515, 0.0, -0.5 * d - 1e-3 - R_s);
  m.obstacles = {ball};
  // Free, x = 0.515 would sag 6.6 mm (P x^2 (3 L - x) / (6 B)): into the sphere, not past it
  // (a rod that passed through a small obstacle entirely is not detected by this check).
  m.tip_force_W_N = Vector3d(0.0, 0.0, -0.01);
  const ContactRun coarse = solve_model(m, options(16));
  ASSERT_TRUE(coarse.summary.converged()) << coarse.summary.message;
  EXPECT_FALSE(coarse.result.converged);
  EXPECT_EQ(coarse.result.status, "passes_between_contact_points");
  EXPECT_NE(coarse.result.message.find("\"ball\""), std::string::npos) << coarse.result.message;
  EXPECT_GT(coarse.result.contacts[0].core_penetration_between_m, 0.5 * d);
  // Nodes every 1/512 m: a few of them on the sphere.
  const ContactRun fine = solve_model(m, options(256));
  ASSERT_TRUE(fine.summary.converged()) << fine.summary.message;
  EXPECT_TRUE(fine.result.converged) << fine.result.message;
  EXPECT_TRUE(fine.result.contacts[0].in_contact());
  EXPECT_LT(fine.result.contacts[0].core_penetration_between_m, 0.5 * 0.5 * d);
}

// --- (c) The clamp reaction without obstacles ---------------------------------------------------

TEST(BeamFeContact, BaseReactionBalancesWeightAndTipLoadsWithoutObstacles) {
  rod::RodModel m = horizontal_rod(2e-3, 0.1);
  m.gravity_W_m_s2 = Vector3d(0.0, -2.0, -kG);
  m.tip_force_W_N = Vector3d(0.01, 0.02, -0.05);
  m.tip_moment_W_Nm = Vector3d(0.001, -0.002, 0.003);
  m.tip_mass_kg = 0.003;
  const Options opt = options(16);
  const ContactRun run = solve_model(m, opt);
  ASSERT_TRUE(run.summary.converged()) << run.summary.message;
  EXPECT_TRUE(run.result.contacts.empty());
  const Solver solver(m, opt);
  expect_global_balance(m, solver, run.result, run.state, rod::Loads::from_model(m));
  // Against the clamp's share of the total load (large deflection: a 1 m steel wire sags).
  const Vector3d total =
      m.length_m * m.weight_per_length_W_N_m() + m.tip_force_W_N + m.tip_mass_kg * m.gravity_W_m_s2;
  EXPECT_LT((run.result.base_reaction->force_W_N + total).norm(), 1e-9 * total.norm());
}

// --- (d) Warm-started sweep across contact onset ------------------------------------------------

TEST(BeamFeContact, WarmStartedSweepAcrossContactOnsetIsContinuous) {
  // A steel rod (d = 10 mm) H = 5 mm above the floor, tip load P: the tip touches at P_on =
  // H / (L^3 / (3 B) + L / S); beyond it the floor takes P - P_on (small deflection: the
  // rod's tip stays at H, held by P_on). Tip slope ~1.5 H / L = 7.5e-3: geometric error of
  // the linear law ~slope^2 ~ 6e-5 of P.
  const double d = 10e-3, H = 5e-3;
  rod::RodModel m = horizontal_rod(d, H + 0.5 * d);
  m.obstacles = {testing::plane_obstacle()};
  const double B = m.bending_torsion_stiffness()[0];
  const double S = m.shear_extension_stiffness()[1];
  const double L = m.length_m;
  const double P_on = H / (L * L * L / (3.0 * B) + L / S);
  const double slope = 1.5 * H / L;
  const Options opt = options(16);
  const Solver solver(m, opt);
  State st;  // one state across the sweep: warm starts keep the multipliers
  double previous_force = 0.0, previous_P = 0.0;
  for (const double f : {0.5, 0.9, 0.99, 1.01, 1.1, 1.5, 2.0, 3.0, 1.2, 0.8}) {
    const double P = f * P_on;
    rod::Loads loads = rod::Loads::from_model(m);
    loads.tip_force_W_N = Vector3d(0.0, 0.0, -P);
    const Summary sum = solver.solve(loads, st);
    ASSERT_TRUE(sum.converged()) << sum.message;
    const rod::Result res = solver.make_result(loads, st, sum);
    const rod::ContactResult& c = res.contacts.at(0);
    const double expected = std::max(0.0, P - P_on);
    std::printf(
        "  P / P_on = %.2f: floor force %.6e N (linear law %.6e N), %d iterations, %d "
        "load step(s), contact %s\n",
        f, c.force_W_N.z(), expected, sum.iterations, sum.load_steps,
        c.in_contact() ? "yes" : "no");
    if (f < 1.0) {
      // Open: exactly no force (the multipliers are zero, not small).
      EXPECT_FALSE(c.in_contact());
      EXPECT_EQ(c.force_W_N.norm(), 0.0);
      EXPECT_EQ(c.max_penetration_m, 0.0);
    } else {
      ASSERT_TRUE(c.in_contact());
      ASSERT_EQ(c.regions.size(), 1u);
      EXPECT_EQ(c.regions[0].s0_m, L);  // the tip node only
    }
    EXPECT_NEAR(c.force_W_N.z(), expected, 2.0 * slope * slope * P);
    // Continuity: the floor force changes by at most the load's change (its slope is 0 or 1).
    EXPECT_LE(std::abs(c.force_W_N.z() - previous_force),
              std::abs(P - previous_P) * (1.0 + 2.0 * slope * slope));
    previous_force = c.force_W_N.z();
    previous_P = P;
    expect_global_balance(m, solver, res, st, loads);
  }
}

// --- (e) A rectangular section's corner on a plane ----------------------------------------------

TEST(BeamFeContact, SquareSectionRolledOnItsEdgeTouchesThePlaneWithItsCorner) {
  // A square steel rod (side 10 mm) rolled 30 degrees about its axis: its lowest outline point
  // is the corner at body (-a/2, -a/2), (a/2)(cos 30 + sin 30) below the centerline. Tip load P
  // = 2 P_on presses the tip corner on the floor H = 5 mm below it.
  const double side = 10e-3, H = 5e-3, roll = 30.0 * units::kPi / 180.0;
  const double depth = 0.5 * side * (std::cos(roll) + std::sin(roll));
  rod::RodModel m = testing::square_rod(1.0, side, kSteelE_Pa, kSteelPoisson, kSteelDensity);
  m.R_WB0 = horizontal_rod(side, 0.0).R_WB0 * so3::exp(Vector3d(0.0, 0.0, roll));
  m.base_position_W_m = Vector3d(0.0, 0.0, H + depth);
  m.obstacles = {testing::plane_obstacle()};
  const double B = m.bending_torsion_stiffness()[0];  // square: the same about every axis
  const double S = m.shear_extension_stiffness()[0];
  const double L = m.length_m;
  const double P_on = H / (L * L * L / (3.0 * B) + L / S);
  const double P = 2.0 * P_on;
  m.tip_force_W_N = Vector3d(0.0, 0.0, -P);
  const Options opt = options(16);
  const ContactRun run = solve_model(m, opt);
  ASSERT_TRUE(run.summary.converged()) << run.summary.message;
  const Solver solver(m, opt);
  const std::vector<rod::ContactSample> samples =
      solver.discretization().contact_samples(run.state, 0);
  // Eight candidates per section (rod::section_gaps): one of them, at the tip, carries force.
  ASSERT_EQ(samples.size(), 8u * (solver.discretization().node_count() - 1));
  std::vector<rod::ContactSample> loaded;
  for (const rod::ContactSample& smp : samples)
    if (smp.force_W_N.norm() > 0.0) loaded.push_back(smp);
  ASSERT_EQ(loaded.size(), 1u);
  const rod::ContactSample& tip = loaded[0];
  EXPECT_EQ(tip.s_m, m.length_m);
  ASSERT_GT(tip.force_W_N.z(), 0.0);
  // The touching point is the corner (-a/2, -a/2) of the tip section.
  const Matrix3d R_tip = run.state.q_WB.back().toRotationMatrix();
  const Vector3d corner_B = R_tip.transpose() * (tip.point_W_m - run.state.p_W_m.back());
  EXPECT_NEAR(corner_B.x(), -0.5 * side, 1e-12);
  EXPECT_NEAR(corner_B.y(), -0.5 * side, 1e-12);
  EXPECT_NEAR(corner_B.z(), 0.0, 1e-12);
  EXPECT_NEAR(tip.point_W_m.z(), 0.0, 1e-12);  // on the floor (gap ~ row tolerance / k)
  // The corner force twists the rod (moment arm (a/2)(cos 30 - sin 30) about its axis), which
  // lowers the corner by ~(a/2)(cos - sin) * twist: with twist = F (a/2)(cos - sin) L / GJ that
  // changes the tip's floor force by a relative ~ (a/2)^2 (cos - sin)^2 3 B / (GJ L^2) ~ 1e-6;
  // the geometric error of the linear law is ~slope^2 (slope ~ 1.5 H / L).
  const double slope = 1.5 * H / L;
  std::printf("  corner force %.6e N (linear law %.6e N), twist %.3e rad, %d iterations\n",
              tip.force_W_N.z(), P - P_on, so3::log(Matrix3d(m.R_WB0.transpose() * R_tip)).z(),
              run.summary.iterations);
  EXPECT_NEAR(tip.force_W_N.z(), P - P_on, 2.0 * slope * slope * P);
  // The clamp carries the torsion of the corner force: about world x it is -(c x F)_x.
  expect_global_balance(m, solver, run.result, run.state, rod::Loads::from_model(m));
}

TEST(BeamFeContact, HeavySquareRodLyingOnAFaceIsHeldByItsTwoLowerCorners) {
  // A square steel rod (side 2 mm), face down, 2 mm above the floor under its weight: the
  // same small-slope closed form as the round rod (B = E a^4 / 12); each node on the floor is
  // held by the two corners of its lower face (rod::section_gaps), which share the load
  // equally (no torsion: the rod's plane of symmetry is vertical).
  const double side = 2e-3, H = 2e-3;
  rod::RodModel m = testing::square_rod(1.0, side, kSteelE_Pa, kSteelPoisson, kSteelDensity);
  m.R_WB0 = horizontal_rod(side, 0.0).R_WB0;
  m.base_position_W_m = Vector3d(0.0, 0.0, H + 0.5 * side);
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles = {testing::plane_obstacle()};
  const Options opt = options(64);
  const ContactRun run = solve_model(m, opt);
  ASSERT_TRUE(run.summary.converged()) << run.summary.message;
  const double B = m.bending_torsion_stiffness()[0];
  const double q = -m.weight_per_length_W_N_m().z();
  const HeavyRodOnFloor cf = heavy_rod_closed_form(B, q, H);
  const double h = m.length_m / opt.elements;
  const double allowed = cf.max_slope * cf.max_slope + std::pow(h / cf.free_span_m, 2) +
                         (2 * opt.elements + 1) * run.summary.residual_inf / (q * cf.free_span_m);
  const double force_error = run.result.base_reaction->force_W_N.z() / cf.clamp_force_N - 1.0;
  const double moment_error = -run.result.base_reaction->moment_W_Nm.y() / cf.clamp_moment_Nm - 1.0;
  std::printf("  square rod: clamp force err %+.3e, moment err %+.3e (bound %.1e), %d iterations\n",
              force_error, moment_error, allowed, run.summary.iterations);
  EXPECT_LT(std::abs(force_error), allowed);
  EXPECT_LT(std::abs(moment_error), allowed);
  const Solver solver(m, opt);
  const std::vector<rod::ContactSample> samples =
      solver.discretization().contact_samples(run.state, 0);
  const LoadCase lc = solver.discretization().load_case(rod::Loads::from_model(m));
  const double row_tolerance =
      opt.tolerance_abs +
      opt.tolerance_rel * solver.discretization().residual_scale(run.state, lc, 1.0) +
      solver.discretization().round_off_floor().force;
  int loaded_nodes = 0;
  for (std::size_t k = 0; k < samples.size(); k += 8) {
    // Corners (+x,+y), (-x,+y), (-x,-y), (+x,-y): body -y is down, so (-x,-y) and (+x,-y).
    const double f_left = samples[k + 2].force_W_N.z(), f_right = samples[k + 3].force_W_N.z();
    for (const int c : {0, 1, 4, 5, 6, 7}) EXPECT_EQ(samples[k + c].force_W_N.norm(), 0.0);
    if (f_left + f_right == 0.0) continue;
    ++loaded_nodes;
    EXPECT_NEAR(f_left, f_right, 2.0 * row_tolerance) << "s = " << samples[k].s_m;
  }
  EXPECT_GT(loaded_nodes, opt.elements / 2);
  expect_global_balance(m, solver, run.result, run.state, rod::Loads::from_model(m));
}

// --- The contact tangent ------------------------------------------------------------------------

TEST(BeamFeContact, ContactTangentMatchesFiniteDifferencesForActiveAndOpenPairs) {
  // A soft rolled square rod (E = 1e5 Pa: internal forces ~0.1 N, so that central differences
  // of the residual keep round-off ~eps 0.1 N / 1e-7 ~ 1e-10) over a floor and a sphere, nodes
  // moved so that some pairs penetrate (active, lambda > 0), some are open (lambda = 0) and one
  // is open with lambda != 0 (a pair leaving the set); no pair sits at lambda = k g, where the
  // row switches.
  const double side = 10e-3, roll = 0.4;
  rod::RodModel m = testing::square_rod(1.0, side, 1e5, 0.3, 1000.0);
  m.R_WB0 = horizontal_rod(side, 0.0).R_WB0 * so3::exp(Vector3d(0.0, 0.0, roll));
  m.base_position_W_m = Vector3d(0.0, 0.0, 0.02);
  rod::Obstacle ball;
  ball.name = "ball";
  ball.type = rod::Obstacle::Type::kSphere;
  ball.radius_m = 0.05;
  ball.point_W_m = Vector3d(0.5, 0.01, 0.08);
  m.obstacles = {testing::plane_obstacle(), ball};
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  Options opt;
  opt.elements = 3;
  const Discretization disc(m, opt);
  const LoadCase lc = disc.load_case(rod::Loads::from_model(m));
  State st = disc.reference_state();
  std::mt19937 gen(5u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 1; k < disc.node_count(); ++k) {
    st.p_W_m[k] += Vector3d(0.003 * u(gen), 0.003 * u(gen), -0.03 * k / disc.node_count());
    st.q_WB[k] =
        (st.q_WB[k] * so3::exp_quaternion(Vector3d(0.1 * u(gen), 0.1 * u(gen), 0.1 * u(gen))))
            .normalized();
  }
  st.p_W_m[3] += Vector3d(0.0, 0.0, 0.06);  // node 3 inside the ball
  int active = 0, open = 0;
  for (int j = 0; j < disc.contact_count(); ++j) {
    const double g = disc.contact_pair(st, j).gap_m;
    st.contact_lambda_N[j] = g < 0.0 ? 0.5 + 0.1 * j : (j == 1 ? -0.3 : 0.0);
    const double margin = st.contact_lambda_N[j] - disc.contact_stiffness_N_m() * g;
    ASSERT_GT(std::abs(margin), 1e-3) << "pair " << j;
    (margin > 0.0 ? active : open) += 1;
  }
  ASSERT_GT(active, 1);
  ASSERT_GT(open, 1);
  for (const auto rows :
       {Discretization::ContactRows::kComplementarity, Discretization::ContactRows::kOpen}) {
    Eigen::SparseMatrix<double> K;
    disc.residual(st, lc, 1.0, &K, rows);
    const MatrixXd K_fd = test_support::jacobian(
        [&](const VectorXd& dx) {
          State t = st;
          disc.retract(t, dx);
          return disc.residual(t, lc, 1.0, nullptr, rows);
        },
        VectorXd::Zero(disc.dof_count()), 1e-7);
    // Column-wise relative error: the tangent's own central differences (steps 1e-7 L, 1e-5
    // rad) are accurate to ~1e-8, the outer ones to ~1e-8: 1e-6.
    const MatrixXd Kd(K);
    double worst = 0.0;
    for (int j = 0; j < Kd.cols(); ++j) {
      const double scale = std::max(K_fd.col(j).lpNorm<Eigen::Infinity>(), 1e-300);
      const double e = (Kd.col(j) - K_fd.col(j)).lpNorm<Eigen::Infinity>() / scale;
      worst = std::max(worst, e);
    }
    EXPECT_LT(worst, 1e-6);
  }
}

// --- Warm starts, status ------------------------------------------------------------------------

TEST(BeamFeContact, WarmStartKeepsTheMultipliersAndIsOneNewtonSolve) {
  rod::RodModel m = horizontal_rod(2e-3, 1e-3 + 1e-3);
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles = {testing::plane_obstacle()};
  const Solver solver(m, options(32));
  State st;
  const rod::Loads loads = rod::Loads::from_model(m);
  const Summary first = solver.solve(loads, st);
  ASSERT_TRUE(first.converged()) << first.message;
  ASSERT_EQ(st.contact_lambda_N.size(), static_cast<std::size_t>(64));
  const std::vector<double> lambda = st.contact_lambda_N;
  const Summary again = solver.solve(loads, st);
  ASSERT_TRUE(again.converged()) << again.message;
  EXPECT_EQ(again.load_steps, 1);
  EXPECT_LE(again.iterations, 1);
  for (std::size_t j = 0; j < lambda.size(); ++j)
    EXPECT_NEAR(st.contact_lambda_N[j], lambda[j], 1e-9) << j;
  EXPECT_STREQ(to_string(Summary::Status::kContactNotSettled), "contact_not_settled");
}

TEST(BeamFeContact, AContactSetThatDoesNotSettleIsReportedWithTheLastIterate) {
  // No contact change allowed: every load step that finds the floor fails; the solve ends with
  // contact_not_settled and the last iterate of the failed step (touching the floor).
  rod::RodModel m = horizontal_rod(2e-3, 1e-3 + 1e-3);
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles = {testing::plane_obstacle()};
  Options opt = options(16);
  opt.max_contact_changes = 0;
  const Solver solver(m, opt);
  State st;
  const rod::Loads loads = rod::Loads::from_model(m);
  const Summary sum = solver.solve(loads, st);
  EXPECT_EQ(sum.status, Summary::Status::kContactNotSettled);
  EXPECT_NE(sum.message.find("max_contact_changes"), std::string::npos) << sum.message;
  EXPECT_GT(sum.load_factor, 0.0);
  EXPECT_EQ(st.load_factor, sum.load_factor);
  bool touching = false;
  for (const double lambda : st.contact_lambda_N) touching = touching || lambda > 0.0;
  EXPECT_TRUE(touching);
  const rod::Result res = solver.make_result(loads, st, sum);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.status, "contact_not_settled");
  opt.max_contact_changes = -1;
  EXPECT_THROW(Solver(m, opt), InputError);
}

TEST(BeamFeContact, DynamicsRejectsObstacles) {
  rod::RodModel m = horizontal_rod(2e-3, 0.01);
  m.obstacles = {testing::plane_obstacle()};
  DynamicsOptions o;
  EXPECT_THROW(BeamDynamics(m, o), DomainError);
}

/// Median wall time of `repeats` cold solves [s] and the last summary.
double median_solve_time(const rod::RodModel& m, const Options& opt, Summary& last) {
  std::vector<double> times;
  for (int i = 0; i < 5; ++i) {
    State st;
    last = Solver(m, opt).solve(rod::Loads::from_model(m), st);
    times.push_back(last.wall_time_s);
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

TEST(BeamFeContact, CostOfAContactSolveAgainstTheSameSolveWithoutTheObstacle) {
  // Informational (printed, not asserted: timings depend on the machine): a cold solve with
  // the obstacle against the same model without it.
  const double d = 10e-3, H = 5e-3;
  for (const int elements : {16, 128}) {
    rod::RodModel m = horizontal_rod(d, H + 0.5 * d);
    const double B = m.bending_torsion_stiffness()[0];
    m.tip_force_W_N = Vector3d(0.0, 0.0, -2.0 * 3.0 * B * H);  // twice the onset load
    m.obstacles = {testing::plane_obstacle()};
    rod::RodModel free = m;
    free.obstacles.clear();
    Summary with, without;
    const double t_with = median_solve_time(m, options(elements), with);
    const double t_without = median_solve_time(free, options(elements), without);
    ASSERT_TRUE(with.converged()) << with.message;
    ASSERT_TRUE(without.converged()) << without.message;
    std::printf(
        "  tip on the floor, %3d elements: %.2e s (%d iterations, %d load steps) vs "
        "%.2e s without the floor (%d iterations, %d load steps): x%.1f\n",
        elements, t_with, with.iterations, with.load_steps, t_without, without.iterations,
        without.load_steps, t_with / t_without);
  }
  for (const int elements : {32, 128}) {
    rod::RodModel m = horizontal_rod(2e-3, 1e-3 + 1e-3);
    m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
    m.obstacles = {testing::plane_obstacle()};
    rod::RodModel free = m;
    free.obstacles.clear();
    Summary with, without;
    const double t_with = median_solve_time(m, options(elements), with);
    const double t_without = median_solve_time(free, options(elements), without);
    ASSERT_TRUE(with.converged()) << with.message;
    ASSERT_TRUE(without.converged()) << without.message;
    std::printf(
        "  heavy rod on the floor, %3d elements: %.2e s (%d iterations, %d load steps) "
        "vs %.2e s hanging free (%d iterations, %d load steps): x%.1f\n",
        elements, t_with, with.iterations, with.load_steps, t_without, without.iterations,
        without.load_steps, t_with / t_without);
  }
}

}  // namespace
}  // namespace tcasim::beam_fe
