// The one call shape of both methods (method/method.hpp, method/dynamics.hpp): the same checks
// run on the shooting method and on the beam FE (typed tests), and the dispatch gives the
// numbers of each method's own solver.
#include "method/method.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "method/dynamics.hpp"
#include "rod/loads.hpp"
#include "support/rod_models.hpp"

namespace tcasim::method {
namespace {

using test_support::sag;
using test_support::steel_cantilever_with_strings;

/// Coarse settings of each method for fast runs.
template <class Options>
Options coarse_dynamics(double dt_s);
template <>
cosserat::DynamicsOptions coarse_dynamics(double dt_s) {
  cosserat::DynamicsOptions o;
  o.dt_s = dt_s;
  o.steps = 20;
  return o;
}
template <>
beam_fe::DynamicsOptions coarse_dynamics(double dt_s) {
  beam_fe::DynamicsOptions o;
  o.dt_s = dt_s;
  o.elements = 4;
  return o;
}

template <class Options>
class BothDynamics : public ::testing::Test {};
using DynamicsMethods = ::testing::Types<cosserat::DynamicsOptions, beam_fe::DynamicsOptions>;
TYPED_TEST_SUITE(BothDynamics, DynamicsMethods);

// The trajectory CSV of either method: the header of `tcasim simulate`, the row of t = 0, every
// output_every-th step and the last; a failing step ends the rows with a "# time step ...
// failed (STATUS)" line.
TYPED_TEST(BothDynamics, WriteTheTrajectoryCsvAndEndAFailedRunWithItsReason) {
  const rod::RodModel m = steel_cantilever_with_strings();
  TypeParam o = coarse_dynamics<TypeParam>(1e-3);
  const rod::LoadsAt released = [&m](double t) { return sag(m, t > 0.0 ? 0.0 : 0.02); };
  DynamicSolver d(m, o);
  std::ostringstream os;
  const rod::TrajectoryOutcome s = write_trajectory(d, m, released, 5, 2, os);
  EXPECT_TRUE(s.ok) << s.message;
  std::istringstream is(os.str());
  std::vector<std::string> lines;
  for (std::string line; std::getline(is, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);  // header, t = 0, steps 2, 4, 5
  EXPECT_EQ(lines[0],
            "t_s,tip_x_m,tip_y_m,tip_z_m,kinetic_energy_J,straight_tension_N,straight_elongation_m,"
            "straight_temperature_degC,helix_tension_N,helix_elongation_m,helix_temperature_degC");
  EXPECT_EQ(lines[1].substr(0, 2), "0,");
  EXPECT_EQ(lines[4].substr(0, 6), "0.005,");
  // One Newton iteration cannot absorb the release: the run stops with a reason.
  o.max_iterations = 1;
  DynamicSolver d1(m, o);
  std::ostringstream os1;
  const rod::TrajectoryOutcome s1 = write_trajectory(d1, m, released, 5, 1, os1);
  EXPECT_FALSE(s1.ok);
  EXPECT_EQ(s1.steps_done, 0);
  EXPECT_NE(os1.str().find("# time step to t = 0.001 s failed (" + s1.status + ")"),
            std::string::npos)
      << os1.str();
}

/// Two runs with the same tip mass taken in different ways converge to the same state to the
/// solvers' tolerance (1e-10 of the force scale; their starting points differ): 1e-9 m, 5 orders
/// of magnitude below the tip weight's deflection here (5 cm).
constexpr double kSameState_m = 1e-9;

// Tip mass: unset in the options, both methods take the scenario's (inertia and weight); set,
// it replaces the scenario's.
TYPED_TEST(BothDynamics, TakeTheScenariosTipMassUnlessTheOptionsReplaceIt) {
  rod::RodModel with_mass = steel_cantilever_with_strings();
  with_mass.tip_mass_kg = 0.02;
  const rod::RodModel without = steel_cantilever_with_strings();
  const auto loads = [](const rod::RodModel& m) { return sag(m, 0.0); };
  TypeParam from_scenario = coarse_dynamics<TypeParam>(1e-3);
  TypeParam given = coarse_dynamics<TypeParam>(1e-3);
  given.tip_mass_kg = 0.02;
  TypeParam zero = coarse_dynamics<TypeParam>(1e-3);
  zero.tip_mass_kg = 0.0;
  DynamicSolver a(with_mass, from_scenario), b(without, given), c(with_mass, zero),
      d(without, from_scenario);
  for (DynamicSolver* s : {&a, &b, &c, &d}) {
    ASSERT_TRUE(s->initialize(loads(with_mass)).converged);
  }
  // The tip weight m g bends the cantilever further; a zero override removes it.
  EXPECT_LT((a.tip_position_W_m() - b.tip_position_W_m()).norm(), kSameState_m);
  EXPECT_LT((c.tip_position_W_m() - d.tip_position_W_m()).norm(), kSameState_m);
  EXPECT_LT(a.tip_position_W_m().x(), c.tip_position_W_m().x() - 1e-2);
  // The same after a step (inertia): released loads, the tip mass still hanging.
  rod::Loads step_loads = loads(with_mass);
  step_loads.gravity_W_m_s2 = Eigen::Vector3d(-4.0, 0.0, 0.0);
  for (DynamicSolver* s : {&a, &b}) ASSERT_TRUE(s->step(step_loads).converged);
  EXPECT_LT((a.tip_position_W_m() - b.tip_position_W_m()).norm(), kSameState_m);
  // The tip mass's inertia: the same kinetic energy (to the same relative tolerance).
  EXPECT_NEAR(a.kinetic_energy_J(), b.kinetic_energy_J(), 1e-6 * a.kinetic_energy_J());
}

// Options out of range are refused with the same key in both methods.
TYPED_TEST(BothDynamics, RefuseANegativeTipMassByTheSameKey) {
  const rod::RodModel m = steel_cantilever_with_strings();
  TypeParam o = coarse_dynamics<TypeParam>(1e-3);
  o.tip_mass_kg = -1.0;
  try {
    DynamicSolver d(m, o);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "dynamics.tip_mass_kg");
  }
}

template <class Options>
class BothStatics : public ::testing::Test {};
using StaticMethods = ::testing::Types<cosserat::Options, beam_fe::Options>;
TYPED_TEST_SUITE(BothStatics, StaticMethods);

/// The method's own solver on `loads`, warm-started from `warm` loads first (what
/// StaticSolver does inside).
rod::Result direct(const rod::RodModel& m, const cosserat::Options& o,
                   const std::vector<rod::Loads>& loads) {
  cosserat::ShootingSolver solver(m, o);
  cosserat::Solution sol;
  rod::Result r;
  for (const rod::Loads& l : loads) r = solver.make_result(l, sol, solver.solve(l, sol));
  return r;
}
rod::Result direct(const rod::RodModel& m, const beam_fe::Options& o,
                   const std::vector<rod::Loads>& loads) {
  beam_fe::Solver solver(m, o);
  beam_fe::State st;
  rod::Result r;
  for (const rod::Loads& l : loads) r = solver.make_result(l, st, solver.solve(l, st));
  return r;
}

// A cold solve, then a warm-started one at other loads, through the dispatch: the numbers of
// each method's own solver, bit for bit; reset() makes the next solve cold again.
TYPED_TEST(BothStatics, GiveTheMethodsOwnNumbersColdAndWarm) {
  const rod::RodModel m = steel_cantilever_with_strings();
  const TypeParam options{};
  const std::vector<rod::Loads> loads = {sag(m, 0.0), sag(m, 0.01)};
  StaticSolver solver(m, options);
  EXPECT_STREQ(solver.method(), name(StaticOptions(options)));
  const rod::Result cold = solver.solve(loads[0]);
  const rod::Result warm = solver.solve(loads[1]);
  ASSERT_TRUE(cold.converged && warm.converged) << cold.message << warm.message;
  EXPECT_EQ(cold.tip_position_W_m, direct(m, options, {loads[0]}).tip_position_W_m);
  EXPECT_EQ(warm.tip_position_W_m, direct(m, options, loads).tip_position_W_m);
  EXPECT_EQ(warm.centerline_p_W_m, direct(m, options, loads).centerline_p_W_m);
  solver.reset();
  EXPECT_EQ(solver.solve(loads[1]).tip_position_W_m,
            direct(m, options, {loads[1]}).tip_position_W_m);
  // The tip weight bends the rod further along -x.
  EXPECT_LT(warm.tip_position_W_m.x(), cold.tip_position_W_m.x());
}

}  // namespace
}  // namespace tcasim::method
