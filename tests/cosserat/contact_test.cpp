// Frictionless contact with rigid obstacles in the shooting solver (docs/conventions.md
// "Contact in the shooting method"): small-slope closed forms (a heavy rod lying down on a
// floor, a cantilever propped on a sphere), global balance, a warm sweep through contact
// onset, a rod wrapping a cylinder.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "cosserat/shooting.hpp"
#include "models.hpp"
#include "rod/scenario.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;

/// Steel rod, r = 1 mm, L = 1 m, clamped at `base` with its axis along world +x (body e1
/// along world -z, e2 along +y).
rod::RodModel horizontal_steel_rod(const Vector3d& base) {
  rod::RodModel m = testing::circular_rod(1.0, 0.002, 200e9, 0.3, 7850.0);
  m.name = "steel-contact";
  m.base_position_W_m = base;
  m.R_WB0 << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  return m;
}

double bending_stiffness(const rod::RodModel& m) {
  const double r = 0.001;
  return m.material.youngs_modulus_profile.value(0.0) * kPi * std::pow(r, 4) / 4.0;
}

double weight_per_length(const rod::RodModel& m) {
  return m.material.density_profile.value(0.0) * kPi * 1e-6 * kG;
}

Options grid_options(int steps) {
  Options o;
  o.integrator.steps = steps;
  return o;
}

/// Sum of everything applied to the rod: clamp, weight, tip wrench, contacts (forces, and
/// moments about the base point).
struct Balance {
  Vector3d force = Vector3d::Zero(), moment = Vector3d::Zero();
};
Balance global_balance(const rod::RodModel& m, const rod::Loads& act, const rod::Result& res,
                       const Solution& sol) {
  Balance b;
  EXPECT_TRUE(res.base_reaction.has_value());
  if (!res.base_reaction) return b;
  b.force = res.base_reaction->force_W_N;
  b.moment = res.base_reaction->moment_W_Nm;
  const Vector3d p0 = m.base_position_W_m;
  // The weight q L g acts at the centroid int_0^L p ds / L (the IVP state c(L), integrated
  // with the same steps as the solution).
  const double q = m.material.density_profile.value(0.0) * kPi * 1e-6;
  const Vector3d W = q * m.length_m * act.gravity_W_m_s2;
  const Vector3d c = sol.tip_state.segment<3>(state_layout::kC);
  b.force += W;
  b.moment += (c / m.length_m - p0).cross(W);
  b.force += act.tip_force_W_N;
  b.moment += act.tip_moment_W_Nm + (res.tip_position_W_m - p0).cross(act.tip_force_W_N);
  for (const rod::ContactResult& cr : res.contacts) {
    b.force += cr.force_W_N;
    b.moment += cr.moment_W_Nm;
  }
  return b;
}

/// The global balance holds to what the solve leaves: the tip residual (||r||_inf <=
/// tolerance in units of F_c for forces, F_c L for moments, per component) and the
/// integrator's error in the conserved total wrench, which the solver reports as its
/// equilibrium imbalance (Summary::force_imbalance_W_N, moment_imbalance_W_Nm).
void expect_balance(const rod::RodModel& m, const rod::Loads& act, const rod::Result& res,
                    const Solution& sol, const Summary& s, const ShootingSolver& solver) {
  const Balance b = global_balance(m, act, res, sol);
  const double f = 2.0 * solver.options().tolerance * solver.characteristic_force_N();
  EXPECT_LE(b.force.norm(), f + s.force_imbalance_W_N.norm());
  EXPECT_LE(b.moment.norm(), f * m.length_m + s.moment_imbalance_W_Nm.norm());
  // What remains is the solver's own imbalance (clamp reaction minus everything applied),
  // to round-off of the largest force summed.
  double scale = act.tip_force_W_N.norm() + m.material.density_profile.value(0.0) * kPi * 1e-6 *
                                                act.gravity_W_m_s2.norm() * m.length_m;
  for (const rod::ContactResult& cr : res.contacts) scale += cr.force_W_N.norm();
  EXPECT_LE((b.force + s.force_imbalance_W_N).norm(), 1e-13 * scale);
  EXPECT_LE((b.moment + s.moment_imbalance_W_Nm).norm(), 1e-13 * scale * m.length_m);
  std::printf("  balance: force %.2e N, moment %.2e N m (solver imbalance %.2e N, %.2e N m)\n",
              b.force.norm(), b.moment.norm(), s.force_imbalance_W_N.norm(),
              s.moment_imbalance_W_Nm.norm());
}

struct FloorRun {
  double clamp_force, clamp_moment, touchdown;
  int iterations;
  double time_s, free_time_s;
};

FloorRun floor_run(double H, int steps) {
  const double r = 0.001;
  rod::RodModel m = horizontal_steel_rod(Vector3d(0.0, 0.0, H + r));
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles.push_back(testing::plane_obstacle());
  ShootingSolver solver(m, grid_options(steps));
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  EXPECT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_EQ(res.contacts.size(), 1u);
  FloorRun out{};
  out.clamp_force = res.base_reaction->force_W_N.z();
  out.clamp_moment = -res.base_reaction->moment_W_Nm.y();
  out.touchdown = res.contacts[0].regions.empty() ? 0.0 : res.contacts[0].regions[0].s0_m;
  out.iterations = s.iterations;
  out.time_s = s.wall_time_s;
  // The same solve without the floor (the rod hangs freely), for the cost.
  rod::RodModel free = m;
  free.obstacles.clear();
  ShootingSolver free_solver(free, grid_options(steps));
  Solution free_sol;
  out.free_time_s = free_solver.solve(act, free_sol).wall_time_s;
  expect_balance(m, act, res, sol, s, solver);
  EXPECT_LE(res.contacts[0].max_penetration_m, 1e-10 * m.length_m);
  return out;
}

// (a) A heavy rod clamped horizontally at clearance H above a frictionless floor. Small-slope
// beam theory: the free span l = (72 B H / q)^(1/4) ends where the rod lies flat, the
// touchdown force is q l / 3, the clamp carries 2 q l / 3 and the moment q l^2 / 6.
TEST(ContactFloor, ApproachesSmallSlopeClosedForm) {
  const rod::RodModel ref = horizontal_steel_rod(Vector3d::Zero());
  const double B = bending_stiffness(ref), q = weight_per_length(ref);
  std::printf(
      "H [m]     steps  l [m]    touchdown  err(F_clamp)  err(M_clamp)  iters  time[s]  "
      "no floor[s]\n");
  for (double H : {4e-3, 1e-3, 2.5e-4}) {
    const double l = std::pow(72.0 * B * H / q, 0.25);
    for (int steps : {32, 64, 128, 256}) {
      const FloorRun f = floor_run(H, steps);
      const double eF = f.clamp_force / (2.0 * q * l / 3.0) - 1.0;
      const double eM = f.clamp_moment / (q * l * l / 6.0) - 1.0;
      std::printf("%.2e  %4d  %.5f  %.5f   %+.3e    %+.3e    %3d   %.4f   %.4f\n", H, steps, l,
                  f.touchdown, eF, eM, f.iterations, f.time_s, f.free_time_s);
      // Small-slope theory drops O(slope^2) (the largest slope is below 2 H / l); the grid
      // resolves the touchdown point to h, and the clamp's force and moment to O((h / l)^2)
      // (measured: the point force at the first node stands for the pressure of its cell).
      const double h = 1.0 / steps;
      const double bound = 4.0 * (H / l) * (H / l) + (h / l) * (h / l);
      EXPECT_LE(std::abs(eF), bound) << "H " << H << " steps " << steps;
      EXPECT_LE(std::abs(eM), bound) << "H " << H << " steps " << steps;
      EXPECT_LE(std::abs(f.touchdown - l), h + 4.0 * H * H / l) << "H " << H << " steps " << steps;
    }
  }
}

rod::Obstacle sphere_below(double x, double radius, double gap) {
  rod::Obstacle o;
  o.name = "sphere";
  o.type = rod::Obstacle::Type::kSphere;
  o.radius_m = radius;
  o.point_W_m = Vector3d(x, 0.0, -0.001 - gap - radius);  // rod's underside at z = -r
  o.direction_W = Vector3d::Zero();
  return o;
}

/// The weightless steel cantilever (L = 1 m) with tip load P down, on a sphere whose top is
/// `gap` below the rod's underside at x = a.
rod::RodModel propped_cantilever(double a, double gap) {
  rod::RodModel m = horizontal_steel_rod(Vector3d::Zero());
  m.material.density_profile = rod::Profile(0.0);
  m.obstacles.push_back(sphere_below(a, 0.002, gap));
  return m;
}

// (b) A cantilever with tip load P resting on a point support at x = a (a sphere of radius
// 2 mm, touching in the reference shape): the small-deflection reaction is
// P (3 L - a) / (2 a) (with the rod's shear compliance below). The error falls with P.
// The grid convergence of the floor solution (H = 1 mm) against steps = 1024: the errors
// of the clamp force and moment and their observed orders.
TEST(ContactFloor, GridConvergence) {
  const double H = 1e-3;
  const FloorRun ref = floor_run(H, 1024);
  std::printf("steps  err(F_clamp)  order   err(M_clamp)  order   touchdown\n");
  double eF0 = 0.0, eM0 = 0.0, eF32 = 0.0, eM32 = 0.0;
  for (int steps : {32, 64, 128, 256, 512}) {
    const FloorRun f = floor_run(H, steps);
    const double eF = std::abs(f.clamp_force / ref.clamp_force - 1.0);
    const double eM = std::abs(f.clamp_moment / ref.clamp_moment - 1.0);
    std::printf("%4d   %.3e    %5.2f   %.3e    %5.2f   %.5f\n", steps, eF,
                steps > 32 ? std::log2(eF0 / eF) : 0.0, eM, steps > 32 ? std::log2(eM0 / eM) : 0.0,
                f.touchdown);
    if (steps == 32) {
      eF32 = eF;
      eM32 = eM;
    }
    eF0 = eF;
    eM0 = eM;
  }
  // The touchdown point is resolved to h (first order), and where it falls between two nodes
  // sets the error of the clamp's force and moment: erratic from one grid to the next, but
  // at least first order over the four halvings (measured: 119 and 120 times smaller).
  EXPECT_LE(eF0, eF32 / 16.0);
  EXPECT_LE(eM0, eM32 / 16.0);
  std::printf("1024 touchdown %.5f, %d iterations, %.3f s\n", ref.touchdown, ref.iterations,
              ref.time_s);
}

TEST(ContactSphere, ProppedCantileverReaction) {
  const double a = 0.5, L = 1.0;
  std::vector<double> err;
  for (double P : {4e-2, 2e-2, 1e-2}) {
    const rod::RodModel m = propped_cantilever(a, 0.0);
    rod::Loads act = rod::Loads::from_model(m);
    act.tip_force_W_N = Vector3d(0.0, 0.0, -P);
    ShootingSolver solver(m, grid_options(64));  // a node at x = a
    Solution sol;
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    ASSERT_EQ(res.contacts.size(), 1u);
    ASSERT_EQ(res.contacts[0].regions.size(), 1u);
    EXPECT_EQ(res.contacts[0].regions[0].s0_m, a);  // a point contact at the node at a
    EXPECT_EQ(res.contacts[0].regions[0].s1_m, a);
    // With the rod's shear compliance 1 / GA (the Cosserat rod shears; Euler-Bernoulli's
    // P (3 L - a) / (2 a) is its GA -> infinity limit, 4e-6 higher here): the deflection at a
    // of P at the tip and of R at a.
    const double B = bending_stiffness(m);
    const double GA = m.stiffness_at(0.0).shear_extension.x();
    const double R =
        P * (a * a * (3.0 * L - a) / (6.0 * B) + a / GA) / (a * a * a / (3.0 * B) + a / GA);
    err.push_back(res.contacts[0].force_W_N.z() / R - 1.0);
    // The largest slope: the tip's.
    const double slope = std::abs(res.tip_R_WB.col(2).z());
    std::printf(
        "P %.1e N: reaction %.9e N, closed form %.9e N, rel. error %+.3e, tip slope %.2e, "
        "iterations %d\n",
        P, res.contacts[0].force_W_N.z(), R, err.back(), slope, s.iterations);
    // Small-slope theory drops O(slope^2); the force acts at the touching point of the
    // section, r slope from the node along the rod (the closed form's thin rod has r = 0).
    EXPECT_LE(std::abs(err.back()), slope * slope + 0.001 / a * slope);
    expect_balance(m, act, res, sol, s, solver);
  }
  EXPECT_LT(std::abs(err[1]), std::abs(err[0]));
  EXPECT_LT(std::abs(err[2]), std::abs(err[1]));
}

// (d) A warm-started sweep of the tip load through contact onset: the support force is zero
// before the rod reaches the sphere (2 mm below), then grows continuously, linearly in the
// small-deflection limit: R = P (3 L - a) / (2 a) - 3 B gap / a^3; a few iterations per step.
TEST(ContactSphere, WarmSweepThroughOnset) {
  const double a = 0.5, L = 1.0, gap = 0.002;
  const rod::RodModel m = propped_cantilever(a, gap);
  const double B = bending_stiffness(m);
  const double P_onset = gap * 6.0 * B / (a * a * (3.0 * L - a));
  ShootingSolver solver(m, grid_options(64));
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const int n = 20;
  double previous = 0.0;
  int max_iterations = 0;
  for (int i = 0; i <= n; ++i) {
    const double P = 2.0 * P_onset * i / n;
    act.tip_force_W_N = Vector3d(0.0, 0.0, -P);
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << "step " << i << ": " << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    const double R = res.contacts[0].force_W_N.z();
    const double R_lin =
        std::max(0.0, P * (3.0 * L - a) / (2.0 * a) - 3.0 * B * gap / std::pow(a, 3));
    std::printf("P %.4e N  reaction %.6e N  linear %.6e N  iterations %d  IVPs %d  %.4f s\n", P, R,
                R_lin, s.iterations, s.ivp_count, s.wall_time_s);
    if (P < 0.95 * P_onset) {
      EXPECT_EQ(R, 0.0);
    }
    // Continuity: the reaction never jumps by more than its linear growth over a step.
    EXPECT_LE(R - previous, 1.5 * 2.0 * P_onset / n * (3.0 * L - a) / (2.0 * a));
    EXPECT_GE(R, 0.0);
    previous = R;
    if (i > 0) max_iterations = std::max(max_iterations, s.iterations);
  }
  EXPECT_LE(max_iterations, 6);
}

// (e) A finger bending onto a peg: the rod under a tip load bends over a cylinder (axis
// along y, radius 5 cm) that touches its underside at x = 0.6 m. The circle's touching point is r
// from the centerline along -n, the multipliers are >= 0, no node penetrates, the clamp,
// tip load and peg balance, and the peg force converges as the grid refines.
TEST(ContactCylinder, FingerBendsOverPeg) {
  rod::RodModel m = horizontal_steel_rod(Vector3d::Zero());
  m.material.density_profile = rod::Profile(0.0);
  rod::Obstacle peg;
  peg.name = "peg";
  peg.type = rod::Obstacle::Type::kCylinder;
  peg.radius_m = 0.05;
  peg.direction_W = Vector3d::UnitY();
  peg.point_W_m = Vector3d(0.6, 0.0, -0.001 - 0.05);
  m.obstacles.push_back(peg);
  rod::Loads act = rod::Loads::from_model(m);
  act.tip_force_W_N = Vector3d(0.0, 0.0, -0.3);
  std::vector<double> force;
  for (int steps : {64, 128, 256}) {
    ShootingSolver solver(m, grid_options(steps));
    Solution sol;
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    const rod::ContactResult& c = res.contacts[0];
    ASSERT_TRUE(c.in_contact());
    EXPECT_LE(c.max_penetration_m, 1e-10);
    for (double l : sol.contact_lambda_N) EXPECT_GE(l, -1e-10 * solver.characteristic_force_N());
    expect_balance(m, act, res, sol, s, solver);
    force.push_back(c.force_W_N.norm());
    std::printf(
        "steps %d: peg force %.9f N over s in [%.4f, %.4f] (%zu regions), iterations %d, "
        "%.3f s\n",
        steps, force.back(), c.regions.front().s0_m, c.regions.back().s1_m, c.regions.size(),
        s.iterations, s.wall_time_s);
  }
  // A point contact lies between two nodes and is resolved to the grid: by the propped
  // cantilever's sensitivity |dR/da| = 3 P L / (2 a^2) the force moves by at most that
  // times h when the grid halves.
  const double dR_da = 3.0 * 0.3 * 1.0 / (2.0 * 0.6 * 0.6);
  EXPECT_LE(std::abs(force[1] - force[0]), dR_da * (1.0 / 64));
  EXPECT_LE(std::abs(force[2] - force[1]), dR_da * (1.0 / 128));
}

// A rod clear of its obstacles is solved by the plain solver (planar, coarse levels,
// sensitivities): the same unknowns as without the obstacle, no contact force, a handful of
// IVPs. A rod whose free solution passes through a sphere is not taken for clear (the
// propped cantilever above has its free tip deflection, 0.0084 m at 1e-2 N, far beyond the
// sphere's half thickness under it).
TEST(ContactStart, ClearRodIsTheFreeSolution) {
  rod::RodModel m = horizontal_steel_rod(Vector3d(0.0, 0.0, 0.5));
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles.push_back(testing::plane_obstacle());  // the floor z = 0, 0.5 m below
  rod::RodModel free = m;
  free.obstacles.clear();
  const rod::Loads act = rod::Loads::from_model(m);
  ShootingSolver solver(m, grid_options(64)), free_solver(free, grid_options(64));
  Solution sol, free_sol;
  const Summary s = solver.solve(act, sol);
  const Summary fs = free_solver.solve(act, free_sol);
  ASSERT_TRUE(s.converged()) << s.message;
  ASSERT_TRUE(fs.converged()) << fs.message;
  EXPECT_EQ(sol.unknowns, free_sol.unknowns);
  EXPECT_LE(s.ivp_count, fs.ivp_count + 2);
  const rod::Result res = solver.make_result(act, sol, s);
  ASSERT_EQ(res.contacts.size(), 1u);
  EXPECT_FALSE(res.contacts[0].in_contact());
  for (double l : sol.contact_lambda_N) EXPECT_EQ(l, 0.0);
  // Warm: a sweep point still clear stays on the free path.
  rod::Loads heavier = act;
  heavier.gravity_W_m_s2 *= 1.1;
  const Summary s2 = solver.solve(heavier, sol);
  const Summary fs2 = free_solver.solve(heavier, free_sol);
  ASSERT_TRUE(s2.converged()) << s2.message;
  ASSERT_TRUE(fs2.converged()) << fs2.message;
  EXPECT_EQ(sol.unknowns, free_sol.unknowns);
  EXPECT_LE(s2.ivp_count, fs2.ivp_count + 2);
}

// A contact point force at the tip node of a finger whose TCA ends there: the rod's and the
// strings' parts of the section wrench cancel, and the strain solve behind the force's jump
// must converge to the parts' round-off, not the (small) wrench's. The paper's gripper finger
// pressing a turned wall with its section's corner near the tip (a shipped suite scenario)
// converged only with that; it agrees with the FE.
TEST(ContactPlane, FingerCornerOnWallAtTheTipAgreesWithFe) {
  const rod::RodModel m = rod::read_scenario(
      std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/contact/gripper-finger-wall.json");
  const rod::Loads act = rod::Loads::from_model(m);
  ShootingSolver solver(m, grid_options(100));
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  ASSERT_EQ(res.contacts.size(), 1u);
  ASSERT_TRUE(res.contacts[0].in_contact());
  EXPECT_LE(res.contacts[0].max_penetration_m, 1e-10 * m.length_m);
  for (double l : sol.contact_lambda_N) EXPECT_GE(l, -1e-10 * solver.characteristic_force_N());
  beam_fe::Solver fe(m, beam_fe::Options{});
  beam_fe::State state;
  const beam_fe::Summary fs = fe.solve(act, state);
  ASSERT_TRUE(fs.converged()) << fs.message;
  const rod::Result fr = fe.make_result(act, state, fs);
  // Both at their defaults (100 RK4 steps, 16 quadratic elements), which agree to 1e-8 L
  // here (measured 2.1e-10 m on 20 mm).
  EXPECT_LE((res.tip_position_W_m - fr.tip_position_W_m).norm(), 1e-7 * m.length_m);
  EXPECT_LE((res.contacts[0].force_W_N - fr.contacts[0].force_W_N).norm(),
            1e-6 * res.contacts[0].force_W_N.norm());
  std::printf("tip difference %.3e m, contact force %.6f N (FE %.6f N)\n",
              (res.tip_position_W_m - fr.tip_position_W_m).norm(), res.contacts[0].force_W_N.norm(),
              fr.contacts[0].force_W_N.norm());
}

// A cold solve ramps the loads quasi-statically: a continuation step may not move a node by
// more than L / 4. With larger steps the heavy EcoFlex rod of the suite reached a looped shape
// standing on its tip above the floor (tip x 0.074 m) instead of draping along it, and the
// three-TCA rod stayed on the near side of its sphere instead of sliding past it; both now
// reach the FE's equilibria (whose continuation is independent of this one).
TEST(ContactStart, ColdSolveFollowsTheLoadingPath) {
  for (const char* name : {"soft-rod-floor", "three-tca-sphere"}) {
    const rod::RodModel m = rod::read_scenario(std::string(TCASIM_SOURCE_DIR) +
                                               "/validation/scenarios/contact/" + name + ".json");
    const rod::Loads act = rod::Loads::from_model(m);
    ShootingSolver solver(m, grid_options(100));
    Solution sol;
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << name << ": " << s.message;
    const rod::Result res = solver.make_result(act, sol, s);
    beam_fe::Solver fe(m, beam_fe::Options{});
    beam_fe::State state;
    const beam_fe::Summary fs = fe.solve(act, state);
    ASSERT_TRUE(fs.converged()) << name << ": " << fs.message;
    const rod::Result fr = fe.make_result(act, state, fs);
    // Both at their defaults (measured 2.2e-6 m and 4.5e-5 m apart, the discretizations'
    // difference; the other equilibria were 0.12 m and 0.03 m away).
    EXPECT_LE((res.tip_position_W_m - fr.tip_position_W_m).norm(), 1e-3 * m.length_m) << name;
    std::printf("%s: tip difference %.3e m, %d iterations\n", name,
                (res.tip_position_W_m - fr.tip_position_W_m).norm(), s.iterations);
  }
}

// A contact set that does not settle within max_iterations is a status, with the last
// iterate kept: the heavy rod on the floor needs more than two steps per load step.
TEST(ContactStatus, NotSettledKeepsLastIterate) {
  rod::RodModel m = horizontal_steel_rod(Vector3d(0.0, 0.0, 0.002));
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  m.obstacles.push_back(testing::plane_obstacle());
  Options o = grid_options(64);
  o.max_iterations = 2;
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  EXPECT_EQ(s.status, Summary::Status::kContactNotSettled);
  EXPECT_STREQ(to_string(s.status), "contact_not_settled");
  EXPECT_NE(s.message.find("max_iterations = 2"), std::string::npos) << s.message;
  EXPECT_FALSE(sol.valid);
  ASSERT_EQ(sol.unknowns.size(), solver.unknown_count());
  EXPECT_TRUE(sol.unknowns.allFinite());
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.status, "contact_not_settled");
  EXPECT_EQ(res.contacts.size(), 1u);
}

TEST(ContactOptions, RefusesCvodeWithObstacles) {
  rod::RodModel m = propped_cantilever(0.5, 0.0);
  Options o;
  o.integrator.method = ode::Method::kCvode;
  try {
    ShootingSolver solver(m, o);
    FAIL() << "CVODE with obstacles accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("options.integrator.method"), std::string::npos);
  }
}

// Every result reports the base reaction: without obstacles it balances weight and tip load.
TEST(ContactBaseReaction, BalancesLoadsWithoutObstacles) {
  rod::RodModel m = horizontal_steel_rod(Vector3d(0.1, 0.2, 0.3));
  m.gravity_W_m_s2 = Vector3d(0.0, 0.0, -kG);
  rod::Loads act = rod::Loads::from_model(m);
  act.tip_force_W_N = Vector3d(0.01, 0.02, -0.03);
  act.tip_moment_W_Nm = Vector3d(0.001, -0.002, 0.003);
  ShootingSolver solver(m, grid_options(64));
  Solution sol;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result res = solver.make_result(act, sol, s);
  EXPECT_TRUE(res.contacts.empty());
  expect_balance(m, act, res, sol, s, solver);
}

}  // namespace
}  // namespace tcasim::cosserat
