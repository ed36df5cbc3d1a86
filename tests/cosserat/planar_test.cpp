// Tests of the planar reduction of the shooting solver (cosserat/internal/planar.hpp): its
// sensitivity equations against differences of its RHS, and its solves against the 3-D
// solver on the same discretization.
#include "cosserat/internal/planar.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

// ---- the kernel ----------------------------------------------------------------------

/// A planar rod with n strings (offsets, counts and rest lengths of mixed signs and sizes);
/// the tensions of the strings listed in `directions` are sensitivity directions 3, 4, ...
planar::Rod kernel_rod(int n, const std::vector<int>& directions) {
  planar::Rod rod;
  rod.kn_x = 0.9;
  rod.kn_z = 2.5;
  rod.kw_y = 4e-3;
  for (int i = 0; i < n; ++i) {
    rod.rho.push_back(0.01 * (i % 2 == 0 ? 1.0 + i : -0.5 - i));
    rod.length_ratio.push_back(1.0 + 0.02 * i);
    rod.count.push_back(1.0 + i);
    rod.cT.push_back(0.05 * (1.0 + i) * (i % 3 == 2 ? -0.5 : 1.0));
    rod.direction_of.push_back(-1);
  }
  for (int k = 0; k < static_cast<int>(directions.size()); ++k)
    rod.direction_of[directions[k]] = 3 + k;
  rod.f_x = 0.3;
  rod.f_z = -0.7;
  return rod;
}

/// A bent, stretched, sheared state (q, cos/sin, strains, c, delta) and n_dir sensitivity
/// blocks of moderate size, all deterministic.
VectorXd kernel_state(int dim, int n_dir) {
  VectorXd Y(dim * (1 + n_dir));
  for (int i = 0; i < Y.size(); ++i) Y[i] = 0.3 * std::sin(1.7 * i + 0.4);
  const double th = 0.6;
  Y[planar::kCS] = std::cos(th);
  Y[planar::kCS + 1] = std::sin(th);
  Y[planar::kNu] = 0.05;
  Y[planar::kNu + 1] = -0.07;  // nu_z - 1
  Y[planar::kKappa] = 12.0;
  return Y;
}

VectorXd planar_rhs(const planar::Rod& rod, const VectorXd& y) {
  VectorXd dy(y.size());
  planar::rhs(rod, y.data(), dy.data());
  return dy;
}

/// The rod with the tensions moved by t along direction j (c_i T_i + t c_i for the strings
/// whose tension is direction j).
planar::Rod moved_tensions(planar::Rod rod, int j, double t) {
  for (std::size_t i = 0; i < rod.rho.size(); ++i) {
    if (rod.direction_of[i] == j) rod.cT[i] += t * rod.count[i];
  }
  return rod;
}

/// Central differences agree with exact derivatives to about eps^(2/3) ~ 4e-11 relative
/// (support/finite_difference.hpp); 1e-7 leaves room for the curvature of these maps.
constexpr double kCentralDifferenceError = 1e-7;

void expect_sensitivities_match_differences(int n_act, const std::vector<int>& directions) {
  const planar::Rod rod = kernel_rod(n_act, directions);
  const int dim = planar::kDelta + n_act;
  const int n_dir = 3 + static_cast<int>(directions.size());
  const VectorXd Y = kernel_state(dim, n_dir);
  VectorXd dY(Y.size());
  planar::rhs_sens(rod, dim, n_dir, Y.data(), dY.data());
  const VectorXd y = Y.head(dim);
  EXPECT_LE((dY.head(dim) - planar_rhs(rod, y)).norm(), 1e-15 * planar_rhs(rod, y).norm());
  for (int j = 0; j < n_dir; ++j) {
    const VectorXd Yj = Y.segment(dim * (j + 1), dim);
    auto along = [&](const VectorXd& t) {
      return planar_rhs(moved_tensions(rod, j, t[0]), y + t[0] * Yj);
    };
    const Eigen::MatrixXd fd = test_support::jacobian(along, VectorXd::Zero(1));
    const VectorXd exact = dY.segment(dim * (j + 1), dim);
    EXPECT_LE((exact - fd.col(0)).norm(), kCentralDifferenceError * fd.col(0).norm())
        << "actuators " << n_act << ", direction " << j << "\nexact " << exact.transpose()
        << "\ndifferences " << fd.col(0).transpose();
  }
}

TEST(PlanarKernel, OneStringSensitivitiesAreTheDerivativeOfTheRhs) {
  expect_sensitivities_match_differences(1, {0});  // Sherman-Morrison, a TCA-like unknown
  expect_sensitivities_match_differences(1, {});   // a known tension
}

TEST(PlanarKernel, SeveralStringSensitivitiesAreTheDerivativeOfTheRhs) {
  expect_sensitivities_match_differences(3, {0, 2});  // the 3x3 system by its adjugate
  expect_sensitivities_match_differences(2, {});
}

TEST(PlanarKernel, TipWrenchSensitivitiesAreItsDerivative) {
  for (int n_act : {1, 3}) {
    const planar::Rod rod = kernel_rod(n_act, {0});
    const int dim = planar::kDelta + n_act;
    const int n_dir = 4;
    const VectorXd Y = kernel_state(dim, n_dir);
    const double F_x = 0.2, F_z = -0.4, M_y = 3e-3, kappa_star = -5.0;
    double dw[3 * planar::kMaxDirections];
    planar::tip_wrench_sens(rod, F_x, F_z, dim, n_dir, Y.data(), dw);
    for (int j = 0; j < n_dir; ++j) {
      const VectorXd Yj = Y.segment(dim * (j + 1), dim);
      auto along = [&](const VectorXd& t) {
        const VectorXd yt = Y.head(dim) + t[0] * Yj;
        Vector3d w;
        planar::tip_wrench(moved_tensions(rod, j, t[0]), kappa_star, F_x, F_z, M_y, yt.data(),
                           w.data());
        return VectorXd(w);
      };
      const Eigen::MatrixXd fd = test_support::jacobian(along, VectorXd::Zero(1));
      const Vector3d exact(dw + 3 * j);
      EXPECT_LE((exact - fd.col(0)).norm(), kCentralDifferenceError * fd.col(0).norm())
          << "actuators " << n_act << ", direction " << j;
    }
  }
}

// ---- solves against the 3-D solver ----------------------------------------------------

Options scheme_options(ode::Method method, int steps, int coarse_steps, bool planar_reduction) {
  Options o;
  o.integrator.method = method;
  o.integrator.steps = steps;
  o.coarse_steps = coarse_steps;
  o.planar_reduction = planar_reduction;
  return o;
}

/// The planar and 3-D IVPs are the same discretization and Newton takes the same steps, so
/// the two solutions differ by round-off: about 1e-16 per operation, amplified by the
/// conditioning of the shooting map (about 1e3 here) and accumulated over the steps.
constexpr double kRoundOffRelative = 1e-11;

struct Solved {
  Summary summary;
  Solution solution;
};

Solved solve_with(const rod::RodModel& m, const Options& o, const rod::Loads& act) {
  ShootingSolver solver(m, o);
  Solved s;
  s.summary = solver.solve(act, s.solution);
  return s;
}

/// Weight of a rod [N].
double weight_N(const rod::RodModel& m) {
  return m.mass_per_length_kg_m(0.0) * m.length_m * m.gravity_W_m_s2.norm();
}

void expect_same_solution(const Solved& planar_solve, const Solved& full, const rod::RodModel& m,
                          const std::string& what) {
  const double weight_scale_N = weight_N(m), length_m = m.length_m;
  SCOPED_TRACE(what);
  ASSERT_TRUE(planar_solve.summary.converged()) << planar_solve.summary.message;
  ASSERT_TRUE(full.summary.converged()) << full.summary.message;
  EXPECT_TRUE(planar_solve.summary.planar);
  EXPECT_FALSE(full.summary.planar);
  const VectorXd& xp = planar_solve.solution.unknowns;
  const VectorXd& x3 = full.solution.unknowns;
  ASSERT_EQ(xp.size(), x3.size());
  EXPECT_EQ(xp[1], 0.0);  // nu_y, omega_x, omega_z: exact zeros in the planar solution
  EXPECT_EQ(xp[3], 0.0);
  EXPECT_EQ(xp[5], 0.0);
  // Column scales of the unknowns: strains, curvatures (1/L), tensions.
  EXPECT_LE((xp - x3).lpNorm<Eigen::Infinity>(), kRoundOffRelative * x3.lpNorm<Eigen::Infinity>())
      << "planar " << xp.transpose() << "\n3-D    " << x3.transpose();
  const VectorXd& yp = planar_solve.solution.tip_state;
  const VectorXd& y3 = full.solution.tip_state;
  ASSERT_EQ(yp.size(), y3.size());
  EXPECT_LE((yp - y3).lpNorm<Eigen::Infinity>(), kRoundOffRelative * y3.lpNorm<Eigen::Infinity>())
      << "planar " << yp.transpose() << "\n3-D    " << y3.transpose();
  EXPECT_EQ(planar_solve.summary.iterations, full.summary.iterations);
  EXPECT_EQ(planar_solve.summary.ivp_count, full.summary.ivp_count);
  // The global equilibrium check (it measures the integrator's truncation error) is the same
  // check: its force and moment agree to round-off of the rod's weight W and W L.
  const Vector3d df = planar_solve.summary.force_imbalance_W_N - full.summary.force_imbalance_W_N;
  const Vector3d dm =
      planar_solve.summary.moment_imbalance_W_Nm - full.summary.moment_imbalance_W_Nm;
  EXPECT_LE(df.norm(), kRoundOffRelative * weight_scale_N);
  EXPECT_LE(dm.norm(), kRoundOffRelative * weight_scale_N * length_m);
}

TEST(PlanarReduction, CircularManipulatorMatchesThe3dSolveForEveryScheme) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const rod::Loads act = rod::Loads::from_model(m);
  struct Case {
    ode::Method method;
    int steps, coarse;
  };
  for (const Case c : {Case{ode::Method::kRk4, 32, 4}, Case{ode::Method::kRk6, 10, 4},
                       Case{ode::Method::kRk8, 4, 2}}) {
    expect_same_solution(solve_with(m, scheme_options(c.method, c.steps, c.coarse, true), act),
                         solve_with(m, scheme_options(c.method, c.steps, c.coarse, false), act), m,
                         ode::to_string(c.method));
  }
}

TEST(PlanarReduction, WarmStartedSweepMatchesThe3dSweep) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(25.0));
  ShootingSolver planar_solver(m, scheme_options(ode::Method::kRk8, 4, 2, true));
  ShootingSolver full_solver(m, scheme_options(ode::Method::kRk8, 4, 2, false));
  rod::Loads act = rod::Loads::from_model(m);
  Solved p, f;
  for (int t = 25; t <= 150; t += 5) {
    act.set_temperature_K(0, units::degC_to_K(t));
    p.summary = planar_solver.solve(act, p.solution);
    f.summary = full_solver.solve(act, f.solution);
    expect_same_solution(p, f, m, std::to_string(t) + " degC");
  }
}

/// Two tension strings and a TCA on both sides of the axis (the adjugate path), a rotated and
/// shifted base, in-plane gravity, tip force and tip moment.
rod::RodModel three_string_rod() {
  rod::RodModel m = testing::circular_rod(0.05, 0.008, 60e3, 0.5, 1100.0);
  m.name = "three-string-planar";
  // Body x -> world y, body y -> world -x, body z -> world z (exact entries).
  m.R_WB0 << 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  m.base_position_W_m = {0.1, -0.2, 0.3};
  m.set_reference_curvature({0.0, 2.0, 0.0});
  m.gravity_W_m_s2 = {0.0, 3.0, -9.81};
  testing::add_tension_string(m, "left", -0.002, 0.0, 0.01);
  testing::add_tension_string(m, "right", 0.0025, 0.0, 0.004, 2);
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), 0.003, 0.0, units::degC_to_K(80.0));
  m.actuators.back().rest_length_m = 0.0406;
  return m;
}

TEST(PlanarReduction, SeveralStringsRotatedBaseAndTipLoadsMatchThe3dSolve) {
  const rod::RodModel m = three_string_rod();
  rod::Loads act = rod::Loads::from_model(m);
  act.tip_force_W_N = {0.0, 1e-3, -2e-3};   // in the world y-z plane = body x-z plane
  act.tip_moment_W_Nm = {-1e-5, 0.0, 0.0};  // along world -x = body y
  for (const ode::Method method : {ode::Method::kRk4, ode::Method::kRk8}) {
    const int steps = method == ode::Method::kRk4 ? 32 : 6;
    const int coarse = method == ode::Method::kRk4 ? 4 : 2;
    expect_same_solution(solve_with(m, scheme_options(method, steps, coarse, true), act),
                         solve_with(m, scheme_options(method, steps, coarse, false), act), m,
                         ode::to_string(method));
  }
}

/// Largest entry-wise difference of two sequences of vectors or matrices of equal length.
template <class V>
double largest_difference(const std::vector<V>& a, const std::vector<V>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    d = std::max(d, (a[k] - b[k]).template lpNorm<Eigen::Infinity>());
  return d;
}

// make_result samples a solution in the plane by the planar IVP. From the same unknowns the
// 3-D IVP (a solver without the reduction) must give the same result to round-off: the
// centerline, the tip, the probes (at a sample and between samples, off the axis), the
// elongations and the bending radius; and a load scale other than 1 takes the same path.
TEST(PlanarReduction, ResultsAreSampledInThePlaneAsThe3dIvpSamplesThem) {
  rod::RodModel m = three_string_rod();
  m.probes = {{"mid", 0.5 * m.length_m, {0.001, 0.002, 0.0}},
              {"between", 0.37 * m.length_m, {-0.002, 0.0, 0.001}}};
  rod::Loads act = rod::Loads::from_model(m);
  act.tip_force_W_N = {0.0, 1e-3, -2e-3};
  ShootingSolver planar_solver(m, scheme_options(ode::Method::kRk4, 32, 4, true));
  ShootingSolver full_solver(m, scheme_options(ode::Method::kRk4, 32, 4, false));
  for (const double scale : {1.0, 0.5}) {
    SCOPED_TRACE("load scale " + std::to_string(scale));
    act.load_scale = scale;
    Solution sol;
    const Summary summary = planar_solver.solve(act, sol);
    ASSERT_TRUE(summary.converged()) << summary.message;
    ASSERT_TRUE(summary.planar);
    const rod::Result rp = planar_solver.make_result(act, sol, summary);
    const rod::Result r3 = full_solver.make_result(act, sol, summary);
    ASSERT_TRUE(rp.converged) << rp.message;
    ASSERT_TRUE(r3.converged) << r3.message;
    const double size_m = m.length_m;
    EXPECT_EQ(rp.centerline_s_m, r3.centerline_s_m);
    EXPECT_LE(largest_difference(rp.centerline_p_W_m, r3.centerline_p_W_m),
              kRoundOffRelative * size_m);
    EXPECT_LE(largest_difference(rp.centerline_R_WB, r3.centerline_R_WB), kRoundOffRelative);
    EXPECT_LE((rp.tip_position_W_m - r3.tip_position_W_m).lpNorm<Eigen::Infinity>(),
              kRoundOffRelative * size_m);
    // The reported tip is the last sample and lies in the plane of the base's x-z axes.
    EXPECT_EQ(rp.tip_position_W_m, rp.centerline_p_W_m.back());
    EXPECT_NEAR(m.R_WB0.col(1).dot(rp.tip_position_W_m - m.base_position_W_m), 0.0,
                kRoundOffRelative * size_m);
    ASSERT_EQ(rp.probes.size(), 2u);
    ASSERT_EQ(r3.probes.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_LE((rp.probes[k].position_W_m - r3.probes[k].position_W_m).lpNorm<Eigen::Infinity>(),
                kRoundOffRelative * size_m)
          << rp.probes[k].name;
    }
    ASSERT_EQ(rp.actuators.size(), r3.actuators.size());
    for (std::size_t i = 0; i < rp.actuators.size(); ++i) {
      EXPECT_EQ(rp.actuators[i].tension_N, r3.actuators[i].tension_N);
      EXPECT_NEAR(rp.actuators[i].elongation_m, r3.actuators[i].elongation_m,
                  kRoundOffRelative * size_m);
    }
    ASSERT_EQ(rp.bending_radius_m.has_value(), r3.bending_radius_m.has_value());
    if (rp.bending_radius_m) {
      EXPECT_NEAR(*rp.bending_radius_m, *r3.bending_radius_m,
                  kRoundOffRelative * *r3.bending_radius_m);
    }
  }
}

TEST(PlanarReduction, OutOfPlaneLoadsAndModelsUseThe3dSolver) {
  const rod::RodModel m = three_string_rod();
  const Options o = scheme_options(ode::Method::kRk8, 6, 2, true);
  ShootingSolver solver(m, o);
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  ASSERT_TRUE(solver.solve(act, sol).planar);
  // A tip force leaving the plane (world x = body -y), warm-started from the planar solution
  // (its reduced Jacobian and path are ignored): the 3-D solve, equal to a cold 3-D solve.
  rod::Loads out = act;
  out.tip_force_W_N = {2e-4, 0.0, 0.0};
  const Summary warm = solver.solve(out, sol);
  ASSERT_TRUE(warm.converged()) << warm.message;
  EXPECT_FALSE(warm.planar);
  EXPECT_NE(sol.unknowns[1], 0.0);  // the rod leaves the plane
  const Solved cold = solve_with(m, scheme_options(ode::Method::kRk8, 6, 2, false), out);
  ASSERT_TRUE(cold.summary.converged());
  // Both stop at ||r||_inf <= 1e-10: they agree to that residual times the conditioning.
  constexpr double kSameEquilibrium = 1e-7;
  EXPECT_LE((sol.unknowns - cold.solution.unknowns).norm(),
            kSameEquilibrium * cold.solution.unknowns.norm());
  // Back to planar loads: the warm start's unknowns are out of the plane, so 3-D again.
  EXPECT_FALSE(solver.solve(act, sol).planar);
  // Gravity with a component along the base frame's y (world -x).
  rod::Loads tilted = act;
  tilted.gravity_W_m_s2 = {0.5, 3.0, -9.81};
  Solution fresh;
  EXPECT_FALSE(solver.solve(tilted, fresh).planar);
  // A string off the body x axis makes the model 3-D.
  rod::RodModel off_axis = m;
  off_axis.actuators[0].routing.offset_m.y() = 1e-4;
  ShootingSolver off_solver(off_axis, o);
  Solution off_sol;
  EXPECT_FALSE(off_solver.solve(rod::Loads::from_model(off_axis), off_sol).planar);
}

}  // namespace
}  // namespace tcasim::cosserat
