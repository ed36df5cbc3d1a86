// The stiffness-ratio gate of the shooting solver (docs/conventions.md "Shooting states and
// unknowns"): Mattiasson's cantilever (tip dead load, k = P L^2 / EI = 1..10) with EA = GA =
// ratio EI / L^2, ratio = 1e2, 1e4, ..., 1e14, solved at increasing step counts; the tip error
// must fall with the steps down to round-off whatever the ratio, and reach <= 1e-10 L.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"
#include "support/convergence.hpp"
#include "support/elastica.hpp"

namespace tcasim::cosserat {
namespace {

/// The extensible, shearable rod's tip differs from the inextensible elastica by about
/// k (EI / (EA L^2) + EI / (GA L^2)) L (measured 1.0e-12 L at k = 1, ratio 1e12); below this
/// bound the closed form is the reference. It is near round-off, not just below the 1e-10
/// gate, so that the error can be seen falling to round-off (EA L^2 / EI = 1e14 here).
constexpr double kNegligibleExtension = 2e-13;
/// Newton tolerance of every solve: F_c = EI / L^2 here, so the tip carries an error of
/// about this times L, far below the errors measured.
constexpr double kSolverTolerance = 1e-13;
/// The gate: the finest level's tip error [L].
constexpr double kFinestError = 1e-10;
/// Errors below this [L] are round-off (a few hundred eps over up to 1024 steps) and need not
/// fall further.
constexpr double kRoundOffLevel = 1e-13;
/// RK4's asymptotic range: levels with at least kAsymptoticSteps steps and errors above
/// kAsymptoticErrorFloor [L] have their observed orders checked two-sided (measured: 16 and
/// 32 steps give orders 3.0 to 3.7 for k = 2..10; below ~5e-13 L round-off shows, e.g.
/// order 3.46 from 1.2e-12 to 1.1e-13 L).
constexpr int kAsymptoticSteps = 64;
constexpr double kAsymptoticErrorFloor = 5e-13;
/// RK4 is fourth order: bracket of the observed order in the asymptotic range.
constexpr double kOrder = 4.0;
constexpr double kOrderTolerance = 0.3;
/// Converged reference where extension matters: RK8 at kReferenceSteps, checked against half
/// the steps (its own error estimate) to this bound [L].
constexpr int kReferenceSteps = 512;
constexpr double kReferenceAgreement = 1e-13;

rod::RodModel cantilever(double ratio, double k) {
  const double L = 1.0, EI = 1.0;
  rod::RodModel m = testing::custom_rod(L, ratio * EI / (L * L), ratio * EI / (L * L), EI, EI);
  m.tip_force_W_N = Eigen::Vector3d(k * EI / (L * L), 0.0, 0.0);
  return m;
}

Options options(ode::Method method, int steps, Kinematics kinematics, bool planar) {
  Options o;
  o.integrator.method = method;
  o.integrator.steps = steps;
  o.tolerance = kSolverTolerance;
  o.kinematics = kinematics;
  o.planar_reduction = planar;
  return o;
}

/// Tip position of the converged solve (NaN if it did not converge).
Eigen::Vector3d tip(const rod::RodModel& m, const Options& o) {
  ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  Solution sol;
  const Summary s = solver.solve(act, sol);
  EXPECT_TRUE(s.converged()) << s.message;
  if (!s.converged()) return Eigen::Vector3d::Constant(std::nan(""));
  return sol.tip_state.head<3>();
}

/// A reference tip and the bound of its own error [L].
struct Reference {
  Eigen::Vector3d tip;
  double error_bound;
};

/// The reference tip: the inextensible closed form where extension is negligible (its error
/// is the extensible correction, ~2 k / ratio L), else RK8 at kReferenceSteps (checked against
/// kReferenceSteps / 2).
Reference reference_tip(double ratio, double k) {
  const double L = 1.0;
  const double correction = 2.0 * k / ratio;
  if (correction <= kNegligibleExtension) {
    const test_support::ElasticaTip t = test_support::cantilever_elastica_tip(k);
    return {Eigen::Vector3d(t.deflection * L, 0.0, t.axial * L), correction};
  }
  const rod::RodModel m = cantilever(ratio, k);
  const Eigen::Vector3d fine =
      tip(m, options(ode::Method::kRk8, kReferenceSteps, Kinematics::kFlat, true));
  const Eigen::Vector3d half =
      tip(m, options(ode::Method::kRk8, kReferenceSteps / 2, Kinematics::kFlat, true));
  EXPECT_LE((fine - half).norm(), kReferenceAgreement * L) << "RK8 reference not converged";
  return {fine, kReferenceAgreement};
}

/// Solves at each step count and checks the gate: the error falls at every refinement until
/// it reaches round-off (or the reference's own error), the finest is <= kFinestError, and
/// (check_order, RK4 schemes) the observed orders of the levels in the asymptotic range lie
/// in [kOrder -+ kOrderTolerance].
void expect_error_falls_to_round_off(double ratio, double k, const std::vector<int>& steps,
                                     ode::Method method, Kinematics kinematics, bool planar,
                                     const Reference& ref, bool check_order) {
  const rod::RodModel m = cantilever(ratio, k);
  std::vector<double> h, err;
  for (int n : steps) {
    h.push_back(m.length_m / n);
    err.push_back((tip(m, options(method, n, kinematics, planar)) - ref.tip).norm() / m.length_m);
  }
  const std::string table = test_support::convergence_table(h, err);
  std::printf("[stiff rod] EA L^2/EI = %.0e, k = %g, %s%s\n%s", ratio, k, planar ? "planar" : "3-D",
              kinematics == Kinematics::kLieGroup ? " (Lie)" : "", table.c_str());
  const double floor = std::max(kRoundOffLevel, ref.error_bound);
  for (std::size_t i = 1; i < err.size(); ++i) {
    EXPECT_TRUE(err[i] < err[i - 1] || err[i] <= floor)
        << "error did not fall from " << steps[i - 1] << " to " << steps[i] << " steps\n"
        << table;
  }
  EXPECT_LE(err.back(), kFinestError) << table;
  if (!check_order) return;
  std::vector<double> ha, ea;
  for (std::size_t i = 0; i < err.size(); ++i) {
    // Ten times the reference's error bound: its error then changes the order by < 0.15.
    if (steps[i] >= kAsymptoticSteps &&
        err[i] >= std::max(kAsymptoticErrorFloor, 10.0 * ref.error_bound)) {
      ha.push_back(h[i]);
      ea.push_back(err[i]);
    }
  }
  ASSERT_GE(ha.size(), 2u) << "fewer than two levels in the asymptotic range\n" << table;
  EXPECT_TRUE(test_support::OrderInBracket(ha, ea, kOrder, kOrderTolerance));
}

const std::vector<double> kRatios = {1e2, 1e4, 1e6, 1e8, 1e10, 1e12, 1e14};
const std::vector<int> kRk4Steps = {16, 32, 64, 128, 256, 512, 1024};
const std::vector<int> kRk8Steps = {4, 8, 16, 32, 64};

TEST(StiffRod, PlanarTipErrorFallsWithTheStepsAtEveryStiffnessRatioAndLoad) {
  for (double ratio : kRatios) {
    for (int k = 1; k <= 10; ++k) {
      SCOPED_TRACE(::testing::Message() << "EA L^2/EI = " << ratio << ", k = " << k);
      const Reference ref = reference_tip(ratio, k);
      expect_error_falls_to_round_off(ratio, k, kRk4Steps, ode::Method::kRk4, Kinematics::kFlat,
                                      true, ref, true);
      expect_error_falls_to_round_off(ratio, k, kRk8Steps, ode::Method::kRk8, Kinematics::kFlat,
                                      true, ref, false);
    }
  }
}

TEST(StiffRod, ThreeDimensionalAndLieGroupTipErrorsFallToo) {
  // The 3-D right-hand side and RKMK4 at both ends of the load range (the planar test has
  // all ten loads; together these take about a second).
  for (double ratio : kRatios) {
    for (int k : {1, 10}) {
      SCOPED_TRACE(::testing::Message() << "EA L^2/EI = " << ratio << ", k = " << k);
      const Reference ref = reference_tip(ratio, k);
      expect_error_falls_to_round_off(ratio, k, kRk4Steps, ode::Method::kRk4, Kinematics::kFlat,
                                      false, ref, true);
      expect_error_falls_to_round_off(ratio, k, kRk4Steps, ode::Method::kRk4, Kinematics::kLieGroup,
                                      false, ref, true);
    }
  }
}

}  // namespace
}  // namespace tcasim::cosserat
