// Solver tests: closed forms, classical benchmarks with exact solutions, objectivity,
// mesh convergence orders, locking, input errors and non-convergence.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "models.hpp"
#include "rod/closed_form.hpp"
#include "support/convergence.hpp"

namespace tcasim::beam_fe {
namespace {

using testing::options;
using testing::run;
using testing::Solved;

using Eigen::Matrix3d;
using Eigen::Vector3d;
constexpr double kPi = units::kPi;

/// Round-off of quantities computed from a converged Newton solution (tolerance_rel
/// 1e-10 by default; here tightened): constant-strain states are exact on any mesh.
constexpr double kExact = 1e-10;

/// Two straight tension strings (one doubled) on a steel-like rod, no gravity.
rod::RodModel straight_strings_rod() {
  rod::RodModel m = testing::stiffness_rod(0.5, 60.0, 25.0, 0.02, 0.03, 0.015);
  testing::add_tension_string(m, "a", 0.01, 0.004, 15.0, 1);
  testing::add_tension_string(m, "b", -0.006, -0.008, 4.0, 2);
  return m;
}

/// docs/conventions.md "Closed form": constant strains and elongations from the tensions.
void closed_form(const rod::RodModel& m, Vector3d& nu, Vector3d& omega,
                 std::vector<double>& delta) {
  std::vector<double> cT;
  for (const rod::Actuator& a : m.actuators) cT.push_back(a.count * a.drive.tension_N);
  const rod::ConstantStrains cf = rod::closed_form_strains(m, cT);
  nu = Vector3d::UnitZ() + cf.e;
  omega = cf.omega;
  delta = rod::closed_form_elongations_m(m, cT);
}

TEST(BeamFeSolver, StraightStringsGiveExactTensionsElongationsAndNodalRotationsOnAnyMesh) {
  const rod::RodModel m = straight_strings_rod();
  Vector3d nu, omega;
  std::vector<double> delta;
  closed_form(m, nu, omega, delta);
  for (const int order : {1, 2}) {
    for (const int elements : {1, 2, 5}) {
      SCOPED_TRACE(::testing::Message() << "order " << order << ", elements " << elements);
      const Options opt = options(elements, order);
      const Solved s = run(m, opt);
      ASSERT_TRUE(s.summary.converged()) << s.summary.message;
      const rod::Result res = make_result(m, opt, s.state, s.summary);
      for (std::size_t i = 0; i < m.actuators.size(); ++i) {
        EXPECT_NEAR(res.actuators[i].tension_N, m.actuators[i].drive.tension_N, 0.0);
        EXPECT_NEAR(res.actuators[i].elongation_m, delta[i], kExact * std::abs(delta[i]));
      }
      for (std::size_t k = 0; k < s.state.s_m.size(); ++k) {
        const Matrix3d R_exact = so3::exp(s.state.s_m[k] * omega);
        EXPECT_LT((s.state.q_WB[k].toRotationMatrix() - R_exact).cwiseAbs().maxCoeff(), kExact);
      }
      for (const PointStrain& p : Discretization(m, opt).strains(s.state)) {
        EXPECT_LT((p.nu_B - nu).cwiseAbs().maxCoeff(), kExact);
        EXPECT_LT((p.omega_B - omega).cwiseAbs().maxCoeff(), kExact);
      }
    }
  }
}

/// Errors of the tip position over meshes `elements`, against `exact`.
std::vector<double> tip_errors(const rod::RodModel& m, int order, const std::vector<int>& elements,
                               const Vector3d& exact,
                               Integration integration = Integration::kReduced) {
  std::vector<double> e;
  for (const int n : elements) {
    Options opt = options(n, order);
    opt.integration = integration;
    const Solved s = run(m, opt);
    EXPECT_TRUE(s.summary.converged()) << s.summary.message;
    e.push_back((s.state.p_W_m.back() - exact).norm());
  }
  return e;
}

std::vector<double> mesh_sizes(double L, const std::vector<int>& elements) {
  std::vector<double> h;
  for (const int n : elements) h.push_back(L / n);
  return h;
}

/// Observed-order brackets of the brief: 2 +- 0.15 (linear), 4 +- 0.3 (quadratic).
constexpr double kLinearOrder = 2.0, kLinearBracket = 0.15;
constexpr double kQuadraticOrder = 4.0, kQuadraticBracket = 0.3;

TEST(BeamFeSolver, StraightStringsTipPositionConvergesAtTheElementOrder) {
  const rod::RodModel m = straight_strings_rod();
  Vector3d nu, omega;
  std::vector<double> delta;
  closed_form(m, nu, omega, delta);
  const Vector3d tip = m.length_m * so3::left_jacobian(m.length_m * omega) * nu;
  const std::vector<int> lin{2, 4, 8, 16}, quad{1, 2, 4, 8};
  const std::vector<double> e1 = tip_errors(m, 1, lin, tip), e2 = tip_errors(m, 2, quad, tip);
  std::printf("straight strings, linear:\n%s",
              test_support::convergence_table(mesh_sizes(m.length_m, lin), e1).c_str());
  std::printf("straight strings, quadratic:\n%s",
              test_support::convergence_table(mesh_sizes(m.length_m, quad), e2).c_str());
  test_support::ExpectOrderInBracket(mesh_sizes(m.length_m, lin), e1, kLinearOrder, kLinearBracket);
  test_support::ExpectOrderInBracket(mesh_sizes(m.length_m, quad), e2, kQuadraticOrder,
                                     kQuadraticBracket);
}

TEST(BeamFeSolver, TcaDriveTensionSolvesTheClosedFormScalarEquation) {
  // Straight TCA, no gravity, no initial bending: delta = -L C T with C = 1/EA + r_x^2/EI_y,
  // T = F_tca(delta, temperature), solved here by scalar Newton on the TCA law.
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 0.0);
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), 0.003, 0.0, units::degC_to_K(90.0));
  const Vector3d Kn = m.shear_extension_stiffness(), Ko = m.bending_torsion_stiffness();
  const double C = 1.0 / Kn.z() + 0.003 * 0.003 / Ko.y();
  const tca::Tca& tca = *m.actuators[0].drive.tca;
  double T = 0.0;
  for (int it = 0; it < 50; ++it) {
    const tca::TensionState f = tca.tension(-m.length_m * C * T, units::degC_to_K(90.0));
    const double g = T - f.tension_N;
    T -= g / (1.0 + f.dF_ddelta_N_m * m.length_m * C);
  }
  for (const int order : {1, 2}) {
    for (const int elements : {1, 2, 5}) {
      SCOPED_TRACE(::testing::Message() << "order " << order << ", elements " << elements);
      const Options opt = options(elements, order);
      const Solved s = run(m, opt);
      ASSERT_TRUE(s.summary.converged()) << s.summary.message;
      const rod::Result res = make_result(m, opt, s.state, s.summary);
      EXPECT_NEAR(res.actuators[0].tension_N, T, kExact * std::abs(T));
      EXPECT_NEAR(res.actuators[0].elongation_m, -m.length_m * C * T,
                  kExact * m.length_m * C * std::abs(T));
      // A heated extension TCA pushes (T < 0) and bends the rod away from its +x offset.
      EXPECT_LT(T, 0.0);
      EXPECT_LT(res.tip_position_W_m.x(), 0.0);
    }
  }
}

/// A rod with EI = GJ and no shear/extension under a pure end moment (n = 0, so nu = e3).
rod::RodModel moment_rod(const Vector3d& M_W) {
  rod::RodModel m = testing::stiffness_rod(1.0, 1e4, 1e4, 1.0, 1.0, 1.0);
  m.tip_moment_W_Nm = M_W;
  return m;
}

/// Discretization error of 16 quadratic elements on a total turning angle <= 2 pi:
/// h^4 convergence from ~1e-3 at one element per radian gives < 1e-6 L.
constexpr double kSixteenQuadraticTip = 1e-6;

void check_constant_curvature(const rod::RodModel& m) {
  const Vector3d omega = m.tip_moment_W_Nm;  // EI = 1: omega_B = M (body = world at the base)
  const Solved s = run(m, options(16, 2));
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  for (std::size_t k = 0; k < s.state.s_m.size(); ++k) {
    EXPECT_LT((s.state.q_WB[k].toRotationMatrix() - so3::exp(s.state.s_m[k] * omega))
                  .cwiseAbs()
                  .maxCoeff(),
              kExact);
  }
  const Vector3d tip = m.length_m * so3::left_jacobian(m.length_m * omega) * Vector3d::UnitZ();
  EXPECT_LT((s.state.p_W_m.back() - tip).norm(), kSixteenQuadraticTip * m.length_m);
}

TEST(BeamFeSolver, HalfRollUpUnderEndMomentPutsTheTipAtTwoLOverPi) {
  const rod::RodModel m = moment_rod({0.0, kPi, 0.0});  // M = pi EI / L
  check_constant_curvature(m);
  const Solved s = run(m, options(16, 2));
  EXPECT_NEAR(s.state.p_W_m.back().x(), 2.0 / kPi, kSixteenQuadraticTip);
  EXPECT_NEAR(s.state.p_W_m.back().z(), 0.0, kSixteenQuadraticTip);
}

TEST(BeamFeSolver, FullRollUpUnderEndMomentClosesTheCircle) {
  check_constant_curvature(moment_rod({0.0, 2.0 * kPi, 0.0}));
}

TEST(BeamFeSolver, EndMomentWithEqualBendingAndTorsionStiffnessGivesAHelix) {
  check_constant_curvature(moment_rod({2.0, -1.0, 3.0}));
}

struct Mattiasson {
  double k, w, u, rotation;  // rotation < 0: not tabulated
};

TEST(BeamFeSolver, MattiassonCantileverMatchesTheElasticaTable) {
  // Inextensible elastica approximated by EA = GA = 1e7 EI/L^2: compliance error <= k 1e-7.
  // Reference values are published to 5 digits (+-5e-6); 32 quadratic elements are
  // converged far below that.
  constexpr double kFiveDigits = 1e-5;
  for (const Mattiasson ref :
       {Mattiasson{1, 0.30172, 0.05643, 0.46135}, Mattiasson{2, 0.49346, 0.16064, -1},
        Mattiasson{5, 0.71379, 0.38763, -1}, Mattiasson{10, 0.81061, 0.55500, 1.43029}}) {
    SCOPED_TRACE(::testing::Message() << "k = " << ref.k);
    rod::RodModel m = testing::stiffness_rod(1.0, 1e7, 1e7, 1.0, 1.0, 1.0);
    m.tip_force_W_N = {ref.k, 0.0, 0.0};
    const Solved s = run(m, options(32, 2));
    ASSERT_TRUE(s.summary.converged()) << s.summary.message;
    const Vector3d tip = s.state.p_W_m.back();
    const Vector3d t = s.state.q_WB.back() * Vector3d::UnitZ();
    std::printf(
        "Mattiasson k = %g: w/L = %.6f (ref %.5f), u/L = %.6f (ref %.5f), rotation = %.6f\n", ref.k,
        tip.x(), ref.w, 1.0 - tip.z(), ref.u, std::atan2(t.x(), t.z()));
    EXPECT_NEAR(tip.x(), ref.w, kFiveDigits);
    EXPECT_NEAR(1.0 - tip.z(), ref.u, kFiveDigits);
    if (ref.rotation > 0) {
      EXPECT_NEAR(std::atan2(t.x(), t.z()), ref.rotation, kFiveDigits);
    }
  }
}

/// A loaded robot: TCA, helical tension string, gravity, initial bending, tip force and moment.
rod::RodModel loaded_manipulator() {
  rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  testing::add_tension_string(m, "helix", 0.002, 0.0, 0.01, 1, 12.0);
  m.tip_force_W_N = {0.0, 2e-3, 0.0};
  m.tip_moment_W_Nm = {0.0, 0.0, 2e-5};
  return m;
}

TEST(BeamFeSolver, RigidlyRotatedProblemGivesTheSameStrainsAndTensions) {
  const rod::RodModel m = loaded_manipulator();
  rod::RodModel r = m;
  const Matrix3d Q = so3::exp(Vector3d(0.3, -1.2, 0.7));
  const Vector3d b(0.1, -0.2, 0.3);
  r.R_WB0 = Q;
  r.base_position_W_m = b;
  r.gravity_W_m_s2 = Q * m.gravity_W_m_s2;
  r.tip_force_W_N = Q * m.tip_force_W_N;
  r.tip_moment_W_Nm = Q * m.tip_moment_W_Nm;
  const Options opt = options(6, 2);
  const Solved a = run(m, opt), c = run(r, opt);
  ASSERT_TRUE(a.summary.converged()) << a.summary.message;
  ASSERT_TRUE(c.summary.converged()) << c.summary.message;
  // Converged to tolerance_rel 1e-12: strains agree to ~1e-10 of their size.
  constexpr double kObjective = 1e-9;
  const std::vector<PointStrain> sa = Discretization(m, opt).strains(a.state);
  const std::vector<PointStrain> sc = Discretization(r, opt).strains(c.state);
  for (std::size_t g = 0; g < sa.size(); ++g) {
    EXPECT_LT((sa[g].nu_B - sc[g].nu_B).norm(), kObjective);
    EXPECT_LT((sa[g].omega_B - sc[g].omega_B).norm(), kObjective * sa[g].omega_B.norm());
  }
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    EXPECT_NEAR(a.state.tensions_N[i], c.state.tensions_N[i],
                kObjective * std::abs(a.state.tensions_N[i]));
  }
  for (std::size_t k = 0; k < a.state.p_W_m.size(); ++k) {
    EXPECT_LT((b + Q * a.state.p_W_m[k] - c.state.p_W_m[k]).norm(), kObjective * m.length_m);
  }
}

TEST(BeamFeSolver, TipErrorConvergesAtOrderTwoForLinearAndFourForQuadraticElements) {
  const rod::RodModel m = loaded_manipulator();
  const std::vector<int> lin{4, 8, 16, 32}, quad{2, 4, 8, 16};
  // Reference: quadratic elements, 8x the finest quadratic mesh (its error is 8^-4 of the
  // finest quadratic one, far below every linear error).
  const Solved ref = run(m, options(128, 2));
  ASSERT_TRUE(ref.summary.converged()) << ref.summary.message;
  const Vector3d tip = ref.state.p_W_m.back();
  const std::vector<double> e1 = tip_errors(m, 1, lin, tip), e2 = tip_errors(m, 2, quad, tip);
  std::printf("loaded manipulator, linear (reduced):\n%s",
              test_support::convergence_table(mesh_sizes(m.length_m, lin), e1).c_str());
  std::printf("loaded manipulator, quadratic (reduced):\n%s",
              test_support::convergence_table(mesh_sizes(m.length_m, quad), e2).c_str());
  test_support::ExpectOrderInBracket(mesh_sizes(m.length_m, lin), e1, kLinearOrder, kLinearBracket);
  test_support::ExpectOrderInBracket(mesh_sizes(m.length_m, quad), e2, kQuadraticOrder,
                                     kQuadraticBracket);
}

TEST(BeamFeSolver, FullIntegrationOfLinearElementsLocksOnASlenderRod) {
  // Thickness t = 1 mm, L = 1 m: EA/EI = 12/t^2. Tip load k = P L^2/EI = 1.
  const double t = 1e-3, E = 1e9;
  rod::RodModel m =
      testing::stiffness_rod(1.0, E * t * t, 0.5 * E * t * t, E * t * t * t * t / 12.0,
                             E * t * t * t * t / 12.0, E * t * t * t * t / 12.0);
  m.tip_force_W_N = {E * t * t * t * t / 12.0, 0.0, 0.0};
  const Solved ref = run(m, options(64, 2));
  ASSERT_TRUE(ref.summary.converged()) << ref.summary.message;
  const Vector3d tip = ref.state.p_W_m.back();
  const double reduced = tip_errors(m, 1, {8}, tip, Integration::kReduced)[0];
  const double full = tip_errors(m, 1, {8}, tip, Integration::kFull)[0];
  std::printf(
      "slender rod, 8 linear elements: tip error reduced %.3e, full %.3e (tip deflection %.4f)\n",
      reduced, full, tip.x());
  // Locking: shear/membrane stiffness 12 (h/t)^2 ~ 2e5 times the bending stiffness.
  constexpr double kMuchLarger = 100.0;
  EXPECT_GT(full, kMuchLarger * reduced);
}

TEST(BeamFeSolver, RejectsZeroElementsAndOrderThree) {
  const rod::RodModel m = straight_strings_rod();
  State st;
  Options bad = options(0, 2);
  try {
    solve(m, bad, st);
    FAIL() << "no InputError for elements = 0";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "elements");
  }
  bad = options(4, 3);
  try {
    solve(m, bad, st);
    FAIL() << "no InputError for order = 3";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "order");
  }
  EXPECT_THROW(parse_integration("exact"), InputError);
}

TEST(BeamFeSolver, NonConvergenceIsReportedWithAReasonAndNoNaN) {
  rod::RodModel m = testing::stiffness_rod(1.0, 1e7, 1e7, 1.0, 1.0, 1.0);
  m.tip_force_W_N = {10.0, 0.0, 0.0};
  Options opt = options(8, 2);
  opt.max_iterations = 1;
  opt.max_load_steps = 4;
  const Solved s = run(m, opt);
  EXPECT_FALSE(s.summary.converged());
  EXPECT_FALSE(s.summary.message.empty());
  const rod::Result res = make_result(m, opt, s.state, s.summary);
  EXPECT_FALSE(res.converged);
  EXPECT_TRUE(res.tip_position_W_m.allFinite());
  // The residual of the returned state, not 0 (which would read as perfect equilibrium).
  ASSERT_TRUE(res.residual.has_value());
  EXPECT_TRUE(std::isfinite(*res.residual));
  EXPECT_GT(*res.residual, 0.0);
  EXPECT_EQ(res.status, "load_step_limit");  // max_load_steps = 4 attempts
  const nlohmann::json j = rod::to_json(res);
  EXPECT_FALSE(j.at("converged").get<bool>());
  EXPECT_EQ(j.at("status"), "load_step_limit");
}

}  // namespace
}  // namespace tcasim::beam_fe

namespace tcasim::beam_fe {
namespace {

TEST(BeamFeSolver, KluUmfpackAndSparseLuGiveTheSameSolution) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  std::vector<Eigen::Vector3d> tips;
  for (const char* name : {"klu", "umfpack", "sparselu"}) {
    Options opt = options(8, 2);
    opt.linear_solver = parse_linear_solver(name);
    const Solved s = run(m, opt);
    ASSERT_TRUE(s.summary.converged()) << name << ": " << s.summary.message;
    tips.push_back(s.state.p_W_m.back());
  }
  // Converged to tolerance_rel 1e-12 of the load scale: tips agree to ~1e-12 of L.
  EXPECT_LT((tips[0] - tips[1]).norm(), 1e-10 * m.length_m);
  EXPECT_LT((tips[0] - tips[2]).norm(), 1e-10 * m.length_m);
  EXPECT_THROW(parse_linear_solver("cholmod"), InputError);
}

TEST(BeamFeSolver, WarmStartFromAConvergedStateNeedsNoNewtonIteration) {
  const rod::RodModel m = loaded_manipulator();
  const Options opt = options(8, 2);
  Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const Summary again = solve(m, opt, s.state);
  EXPECT_TRUE(again.converged());
  EXPECT_EQ(again.iterations, 0);
}

TEST(BeamFeSolver, ResultCarriesMethodDiscretizationTipAndBendingRadius) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const Options opt = options(8, 2);
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const rod::Result res = make_result(m, opt, s.state, s.summary);
  EXPECT_EQ(res.method, "fe");
  ASSERT_EQ(res.discretization.size(), 2u);
  EXPECT_EQ(res.discretization[0].first, "elements");
  EXPECT_EQ(res.discretization[0].second, 8.0);
  EXPECT_EQ(res.discretization[1].first, "order");
  EXPECT_EQ(res.discretization[1].second, 2.0);
  EXPECT_EQ(res.centerline_s_m.size(), 17u);
  EXPECT_EQ(res.tip_position_W_m, s.state.p_W_m.back());
  ASSERT_TRUE(res.bending_radius_m.has_value());
  EXPECT_GT(*res.bending_radius_m, 0.0);
  EXPECT_TRUE(res.message.empty());
}

TEST(BeamFeSolver, ConstantStrainGuessHasTheExactTcaTensionAndNodalRotations) {
  // No gravity, straight TCA and tension strings, precurved: the predictor's tensions solve
  // the closed-form TCA equation and its nodal rotations R0 exp(s omega) are the converged
  // FE ones (exact on any mesh); positions differ only by the interpolation of the arc.
  rod::RodModel m = testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 0.0);
  m.set_reference_curvature({0.2, -0.5, 0.0});
  testing::add_tca_string(m, "tca", testing::manipulator_tca(), 0.003, 0.0, units::degC_to_K(90.0));
  testing::add_tension_string(m, "pull", -0.002, 0.002, 0.01);
  const Options opt = options(5, 2);
  const Discretization disc(m, opt);
  const LoadCase disc_loads = disc.load_case(rod::Loads::from_model(m));
  State guess = disc.reference_state();
  ASSERT_TRUE(disc.constant_strain_guess(disc_loads, 1.0, guess));
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  for (std::size_t i = 0; i < m.actuators.size(); ++i) {
    EXPECT_NEAR(guess.tensions_N[i], s.state.tensions_N[i],
                kExact * std::abs(s.state.tensions_N[i]));
  }
  for (std::size_t k = 0; k < s.state.s_m.size(); ++k) {
    EXPECT_LT((guess.q_WB[k].toRotationMatrix() - s.state.q_WB[k].toRotationMatrix())
                  .cwiseAbs()
                  .maxCoeff(),
              kExact);
  }
  // Helical routing has no constant-strain solution: no guess.
  testing::add_tension_string(m, "helix", 0.002, 0.0, 0.01, 1, 12.0);
  const Discretization helical(m, opt);
  const LoadCase helical_loads = helical.load_case(rod::Loads::from_model(m));
  State untouched = helical.reference_state();
  EXPECT_FALSE(helical.constant_strain_guess(helical_loads, 1.0, untouched));
}

TEST(BeamFeSolver, WarmStartFromAnotherTemperatureConvergesToTheColdStartSolution) {
  const Options opt = options(8, 2);
  Solved warm = run(testing::circular_manipulator(units::degC_to_K(40.0)), opt);
  ASSERT_TRUE(warm.summary.converged()) << warm.summary.message;
  const rod::RodModel hot = testing::circular_manipulator(units::degC_to_K(90.0));
  const Summary s = solve(hot, opt, warm.state);
  ASSERT_TRUE(s.converged()) << s.message;
  const Solved cold = run(hot, opt);
  // Both converged to tolerance_rel 1e-12 of the load scale.
  EXPECT_LT((warm.state.p_W_m.back() - cold.state.p_W_m.back()).norm(), 1e-10 * hot.length_m);
}

}  // namespace
}  // namespace tcasim::beam_fe

namespace tcasim::beam_fe {
namespace {

/// Two converged solves of the same loads (tolerance_rel 1e-12 of the load scale) agree
/// to about 1e-12 of L; 1e-10 L leaves room for the conditioning of the tip position.
constexpr double kSameSolution = 1e-10;

TEST(BeamFeSolver, ModelLoadsOverloadGivesBitwiseTheSameSolve) {
  const rod::RodModel m = loaded_manipulator();
  const Options opt = options(8, 2);
  const Solved old_api = run(m, opt);
  State state;
  const Summary s = solve(m, rod::Loads::from_model(m), opt, state);
  ASSERT_TRUE(s.converged()) << s.message;
  EXPECT_EQ(s.iterations, old_api.summary.iterations);
  EXPECT_EQ(state.p_W_m.back(), old_api.state.p_W_m.back());
  EXPECT_EQ(state.tensions_N, old_api.state.tensions_N);
}

TEST(BeamFeSolver, SweepPointWarmStartedAcrossLoadChangesEqualsAColdSolveOfTheSameLoads) {
  // A temperature sweep of the TCA and a change of the tip force and gravity, one State
  // across the points: each point equals a cold solve of the same loads.
  rod::RodModel m = testing::circular_manipulator(units::degC_to_K(40.0));
  testing::add_tension_string(m, "pull", -0.002, 0.002, 0.01);
  const Options opt = options(8, 2);
  rod::Loads loads = rod::Loads::from_model(m);
  State sweep;
  for (double t_degC : {40.0, 55.0, 70.0, 90.0}) {
    loads.set_temperature_K(0, units::degC_to_K(t_degC));
    loads.set_tension_N(1, 0.01 + 1e-4 * t_degC);
    const Summary warm = solve(m, loads, opt, sweep);
    ASSERT_TRUE(warm.converged()) << t_degC << " degC: " << warm.message;
    State cold;
    const Summary c = solve(m, loads, opt, cold);
    ASSERT_TRUE(c.converged()) << c.message;
    EXPECT_LT((sweep.p_W_m.back() - cold.p_W_m.back()).norm(), kSameSolution * m.length_m)
        << t_degC;
    for (std::size_t i = 0; i < m.actuators.size(); ++i) {
      EXPECT_NEAR(sweep.tensions_N[i], cold.tensions_N[i],
                  kSameSolution * std::abs(cold.tensions_N[i]));
    }
    if (t_degC > 40.0) {
      EXPECT_EQ(warm.load_steps, 1) << "a warm point is one Newton solve at full load";
    }
    // The sweep's result reads the coil contact at the sweep's temperatures.
    const rod::Result res = make_result(m, loads, opt, sweep, warm);
    EXPECT_EQ(res.actuators.size(), m.actuators.size());
  }
  loads.tip_force_W_N = {0.0, 1e-3, 0.0};
  loads.gravity_W_m_s2 = {0.0, 0.0, -9.81};
  ASSERT_TRUE(solve(m, loads, opt, sweep).converged());
  State cold;
  ASSERT_TRUE(solve(m, loads, opt, cold).converged());
  EXPECT_LT((sweep.p_W_m.back() - cold.p_W_m.back()).norm(), kSameSolution * m.length_m);
}

TEST(BeamFeSolver, LoadScaleSolvesTheScaledLoads) {
  rod::RodModel m = loaded_manipulator();
  const Options opt = options(8, 2);
  rod::Loads half = rod::Loads::from_model(m);
  half.load_scale = 0.5;
  State scaled;
  ASSERT_TRUE(solve(m, half, opt, scaled).converged());
  State explicit_half;
  ASSERT_TRUE(solve(m, half.applied(m), opt, explicit_half).converged());
  EXPECT_EQ(scaled.p_W_m.back(), explicit_half.p_W_m.back());
  State full;
  ASSERT_TRUE(solve(m, rod::Loads::from_model(m), opt, full).converged());
  EXPECT_GT((scaled.p_W_m.back() - full.p_W_m.back()).norm(), 1e-6 * m.length_m);
}

TEST(BeamFeSolver, LoadsThatDoNotFitTheModelAreAnInputErrorNamingTheField) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(40.0));
  rod::Loads loads = rod::Loads::from_model(m);
  loads.actuators.pop_back();
  State state;
  try {
    solve(m, loads, options(4, 2), state);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "loads.actuators");
  }
  loads = rod::Loads::from_model(m);
  loads.load_scale = 1.5;
  EXPECT_THROW(solve(m, loads, options(4, 2), state), InputError);
}

TEST(BeamFeSolver, ADefaultSummarySaysItWasNeverRun) {
  const Summary none;
  EXPECT_EQ(none.status, Summary::Status::kNotRun);
  EXPECT_STREQ(to_string(none.status), "not_run");
  EXPECT_FALSE(none.equilibrium_residual.has_value());
}

TEST(BeamFeSolver, CommonResidualOfAConvergedSolveIsWithinItsTolerance) {
  const rod::RodModel m = testing::circular_manipulator(units::degC_to_K(90.0));
  const Options opt = options(8, 2);
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  EXPECT_EQ(s.summary.characteristic_force_N,
            rod::characteristic_force_N(m, rod::Loads::from_model(m)));
  ASSERT_TRUE(s.summary.equilibrium_residual.has_value());
  // Every row is within tolerance_abs + tolerance_rel scale + floor; over F_c that is far below
  // 1e-6.
  EXPECT_LT(*s.summary.equilibrium_residual, 1e-6);
  EXPECT_LE(*s.summary.equilibrium_residual * s.summary.characteristic_force_N,
            s.summary.residual_inf / std::min(1.0, m.length_m));
  const rod::Result res = make_result(m, opt, s.state, s.summary);
  EXPECT_EQ(res.status, "converged");
  EXPECT_EQ(res.residual, s.summary.equilibrium_residual);
}

}  // namespace
}  // namespace tcasim::beam_fe
