// Coil contact in the shooting solver (docs/conventions.md "Closed coils"): a TCA held closed
// is a rigid strut (closed form), a temperature sweep opens it at the onset the TCA library
// predicts for the rod's load, and inverse and grasp solves that start closed still work.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "common/units.hpp"
#include "cosserat/inverse.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"

namespace tcasim::cosserat {
namespace {

/// RK8 with 16 steps on the strut arc (kappa L < 1 rad): truncation far below 1e-12 L, so the
/// closed-form checks see the Newton tolerance only.
Options strut_options() {
  Options o;
  o.integrator.method = ode::Method::kRk8;
  o.integrator.steps = 16;
  o.tolerance = 1e-12;
  return o;
}

/// Tip agreement with the closed form, relative to L: RK8 truncation and Newton tolerance.
constexpr double kClosedFormTip = 1e-10;
/// Strut tension agreement, relative (the residual tolerance 1e-12 F_c, conditioning ~1e2).
constexpr double kClosedFormTension = 1e-9;
/// The onset used by the sweep and inverse tests [degC].
constexpr double kOnset_degC = 60.0;

/// The strut rod whose tendon load keeps the TCA closed exactly up to onset_degC: the load
/// is chosen so that the strut tension equals the blocked force at the onset.
rod::RodModel strut_rod_opening_at(double onset_degC, double t_K) {
  rod::RodModel m = testing::strut_rod(1.0, t_K);
  const testing::StrutClosedForm unit = testing::strut_closed_form(m);  // T_s per newton of load
  const double fb = m.actuators[0].drive.tca->blocked_force(units::degC_to_K(onset_degC));
  m.actuators[1].drive.tension_N = fb / unit.strut_tension_N;
  return m;
}

TEST(ClosedCoils, TcaHeldClosedByALoadAboveItsBlockedForceIsARigidStrut) {
  const double t_K = units::degC_to_K(25.0);
  const rod::RodModel m = testing::strut_rod(0.5, t_K);
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const double fb = m.actuators[0].drive.tca->blocked_force(t_K);
  ASSERT_LT(cf.strut_tension_N, fb);  // the load exceeds what the TCA can hold open
  ShootingSolver solver(m, strut_options());
  const rod::Loads act = rod::Loads::from_model(m);
  // Start away from the closed form (the cold guess already is it): the straight rod with the
  // TCA pushing at its free-coil force, coils open.
  Solution sol;
  sol.valid = true;
  sol.unknowns.resize(7);
  sol.unknowns << 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5 * cf.strut_tension_N;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  EXPECT_GE(s.iterations, 2);
  const rod::Result r = solver.make_result(act, sol, s);
  const double L = m.length_m;
  EXPECT_LE((r.tip_position_W_m - cf.tip_W_m).norm(), kClosedFormTip * L);
  EXPECT_NEAR(r.actuators[0].tension_N, cf.strut_tension_N,
              kClosedFormTension * std::abs(cf.strut_tension_N));
  EXPECT_LE(std::abs(r.actuators[0].elongation_m), kClosedFormTip * L);
  EXPECT_TRUE(r.actuators[0].coils_closed);
  EXPECT_NEAR(r.actuators[0].contact_force_N, fb - cf.strut_tension_N,
              kClosedFormTension * std::abs(cf.strut_tension_N));
  std::printf("[strut] tip err %.2e L, T_s = %.6e N (closed form %.6e), delta = %.2e m, %d its\n",
              (r.tip_position_W_m - cf.tip_W_m).norm() / L, r.actuators[0].tension_N,
              cf.strut_tension_N, r.actuators[0].elongation_m, s.iterations);
}

TEST(ClosedCoils, OpenCoilTcaHeldAtItsClosedLengthNd0IsARigidStrut) {
  // A measured fiber: the coils touch at n d0 < L, delta_c = n d0 - L; the strut holds there.
  const double t_K = units::degC_to_K(25.0);
  const rod::RodModel m = testing::open_coil_strut_rod(0.5, t_K);
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const tca::Tca& tca = *m.actuators[0].drive.tca;
  const double dc = tca.closed_elongation_m(), fc = tca.closed_force(t_K);
  ASSERT_LT(dc, 0.0);
  ASSERT_LT(cf.strut_tension_N, fc);  // the load exceeds what the open coil can hold off
  ShootingSolver solver(m, strut_options());
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  sol.valid = true;
  sol.unknowns.resize(7);
  sol.unknowns << 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5 * cf.strut_tension_N;
  const Summary s = solver.solve(act, sol);
  ASSERT_TRUE(s.converged()) << s.message;
  const rod::Result r = solver.make_result(act, sol, s);
  const double L = m.length_m;
  EXPECT_LE((r.tip_position_W_m - cf.tip_W_m).norm(), kClosedFormTip * L);
  EXPECT_NEAR(r.actuators[0].tension_N, cf.strut_tension_N,
              kClosedFormTension * std::abs(cf.strut_tension_N));
  EXPECT_NEAR(r.actuators[0].elongation_m, dc, kClosedFormTip * L);
  EXPECT_TRUE(r.actuators[0].coils_closed);
  EXPECT_NEAR(r.actuators[0].contact_force_N, fc - cf.strut_tension_N,
              kClosedFormTension * std::abs(cf.strut_tension_N));
}

TEST(ClosedCoils, SweepOpensTheCoilsAtThePredictedOnsetWithAContinuousKink) {
  const rod::RodModel m = strut_rod_opening_at(kOnset_degC, units::degC_to_K(40.0));
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const tca::Tca& tca = *m.actuators[0].drive.tca;
  // The onset the TCA library predicts for the rod's load (the strut force).
  const std::optional<double> onset_K =
      tca.onset_temperature(cf.strut_tension_N, units::degC_to_K(25.0), units::degC_to_K(160.0));
  ASSERT_TRUE(onset_K.has_value());
  EXPECT_NEAR(units::K_to_degC(*onset_K), kOnset_degC, 1e-6);

  ShootingSolver solver(m, strut_options());
  rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const double step_K = 0.5;
  std::vector<double> t_K;
  std::vector<Eigen::Vector3d> tips;
  std::vector<bool> closed;
  int max_iterations = 0;
  for (double t = units::degC_to_K(40.0); t <= units::degC_to_K(80.0) + 1e-9; t += step_K) {
    act.set_temperature_K(0, t);
    const Summary s = solver.solve(act, sol);
    ASSERT_TRUE(s.converged()) << units::K_to_degC(t) << " degC: " << s.message;
    const rod::Result r = solver.make_result(act, sol, s);
    t_K.push_back(t);
    tips.push_back(r.tip_position_W_m);
    closed.push_back(r.actuators[0].coils_closed);
    max_iterations = std::max(max_iterations, s.iterations);
    if (t < *onset_K) {
      // Closed: the rigid-strut state, whatever the temperature.
      EXPECT_TRUE(r.actuators[0].coils_closed) << units::K_to_degC(t);
      EXPECT_LE((r.tip_position_W_m - cf.tip_W_m).norm(), kClosedFormTip * m.length_m)
          << units::K_to_degC(t);
    } else if (t > *onset_K) {
      EXPECT_FALSE(r.actuators[0].coils_closed) << units::K_to_degC(t);
      EXPECT_EQ(r.actuators[0].contact_force_N, 0.0);
      EXPECT_GT(r.actuators[0].elongation_m, 0.0);
    }
  }
  // The kink: no motion before the onset, motion after it, continuous across it (the jump
  // over the onset step is no larger than the open steps that follow).
  std::size_t k_on = 0;
  while (k_on < t_K.size() && t_K[k_on] <= *onset_K) ++k_on;
  ASSERT_GE(k_on, 2u);
  ASSERT_LT(k_on + 2, t_K.size());
  const double before = (tips[k_on - 1] - tips[k_on - 2]).norm();
  const double across = (tips[k_on] - tips[k_on - 1]).norm();
  const double after = (tips[k_on + 1] - tips[k_on]).norm();
  EXPECT_LE(before, kClosedFormTip * m.length_m);
  EXPECT_GT(after, 1e-6 * m.length_m);
  EXPECT_LE(across, after);
  // Semismooth Newton: warm steps through the kink stay cheap.
  EXPECT_LE(max_iterations, 8);
  std::printf(
      "[onset sweep] predicted onset %.6f degC; tip steps before %.2e, across %.2e, after "
      "%.2e m; max Newton iterations %d\n",
      units::K_to_degC(*onset_K), before, across, after, max_iterations);
}

TEST(ClosedCoils, InverseSolveStartingWithClosedCoilsReachesATargetAboveTheOnset) {
  const rod::RodModel m = strut_rod_opening_at(kOnset_degC, units::degC_to_K(40.0));
  const double target_K = units::degC_to_K(75.0);
  ShootingSolver solver(m, strut_options());
  rod::Loads hot = rod::Loads::from_model(m);
  hot.set_temperature_K(0, target_K);
  Solution hs;
  ASSERT_TRUE(solver.solve(hot, hs).converged());
  const Eigen::Vector3d target = hs.tip_state.head<3>();

  rod::Loads act = rod::Loads::from_model(m);  // 40 degC: closed, no temperature sensitivity
  Solution sol;
  InverseOptions o;
  o.actuators = {0};
  o.components = {true, false, false};  // one actuator moves the tip along x
  o.tolerance_m = 1e-11;
  const InverseResult r = solve_inverse(solver, m, target, o, act, sol);
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_NEAR(r.values[0], target_K, 1e-6);
  std::printf("[inverse from closed] %.9f degC (target %.3f), %d iterations, %d forward solves\n",
              units::K_to_degC(r.values[0]), units::K_to_degC(target_K), r.iterations,
              r.forward_solves);
}

TEST(ClosedCoils, GraspSolveStartingWithClosedCoilsFindsTheTemperatureOfTheForce) {
  // The strut finger touches the object at its closed-coil tip, on its -x side: while the
  // coils are closed it does not push; above the onset the heated TCA pushes the tip into it.
  // An onset at 30 degC keeps the finger short of curling: the force grows up to 160 degC.
  rod::RodModel m = strut_rod_opening_at(30.0, units::degC_to_K(25.0));
  rod::TipConstraint held;
  held.position_W_m = testing::strut_closed_form(m).tip_W_m;
  held.normal_W = Eigen::Vector3d(-1.0, 0.0, 0.0);  // from the finger toward the object
  m.tip_constraint = held;
  const Options so = strut_options();
  ShootingSolver cs(m, so);
  Solution bs;
  const double t_force_K = units::degC_to_K(50.0);
  const double f100 = blocked_normal_force_N(cs, m, t_force_K, bs);
  ASSERT_GT(f100, 0.0);
  GraspOptions g;
  g.friction = 1.0;
  g.fingers = 1;
  g.mass_kg = f100 / units::kStandardGravity_m_s2;  // m g / (mu n) = the force at 100 degC
  const GraspResult r = solve_grasp(m, so, g);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.temperature_K, t_force_K, 1e-5);
  ASSERT_TRUE(r.root_temperature_K.has_value());
  EXPECT_NEAR(*r.root_temperature_K, t_force_K, 1e-5);
  std::printf("[grasp from closed] %.7f degC (blocked force %.4e N at 50 degC), %d iterations\n",
              units::K_to_degC(r.temperature_K), f100, r.iterations);
}

}  // namespace
}  // namespace tcasim::cosserat
