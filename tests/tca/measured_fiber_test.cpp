// Unit tests of a TCA with a measured fiber diameter (docs/conventions.md "Measured fiber
// diameter"): the helix of mean diameter D - d0, the closed length n d0 of an open coil, the
// coil contact there, and the geometry checks.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "contact_checks.hpp"
#include "tca/tca.hpp"
#include "test_materials.hpp"

namespace tcasim::tca {
namespace {

using testing::K;
using testing::nylon_monocoil;
using testing::open_monocoil;
using testing::three_thread;
using units::kPi;

/// Same closed-form quantity computed two ways (round-off only).
constexpr double kRoundOffRelTol = 1e-12;
/// Central differences with steps 1e-9 m / 1e-7 N / 1e-3 K on laws varying over ~1 mm /
/// ~1 N / ~100 K: truncation and round-off far below 1e-6 relative, any missing term above.
constexpr double kFdRelTol = 1e-6;

double central_difference(const std::function<double(double)>& f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

std::string input_error_message(const Parameters& p) {
  try {
    (void)Tca(p, nylon_monocoil());
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(MeasuredFiber, HelixOfMeanDiameterGivesTheCoilCountItWasBuiltFrom) {
  const Parameters p = open_monocoil();
  const Tca tca(p, nylon_monocoil());
  const double Dm = 1.632e-3, n = 732.0 * 0.025;
  EXPECT_TRUE(tca.has_measured_fiber_diameter());
  EXPECT_NEAR(tca.coil_count(), n, kRoundOffRelTol * n);
  EXPECT_NEAR(tca.mean_coil_diameter_m(), Dm, kRoundOffRelTol * Dm);
  EXPECT_EQ(tca.initial_fiber_diameter_m(), 0.74e-3);
  // sin(alpha0) = L/l and tan(alpha0) = L/(pi Dm n) describe the same helix.
  EXPECT_NEAR(std::tan(tca.initial_pitch_angle_rad()), 0.025 / (kPi * Dm * n), kRoundOffRelTol);
  EXPECT_NEAR(coil_count_from_pitch(0.025, Dm, tca.initial_pitch_angle_rad()), n,
              kRoundOffRelTol * n);
  // The model's coil radius R = l cos(alpha)/(2 pi n) (the complementary-energy derivation of
  // Eqs. (3)-(4)) is the helix's mean radius at alpha0.
  EXPECT_NEAR(p.fiber_length_m * std::cos(tca.initial_pitch_angle_rad()) / (2.0 * kPi * n),
              0.5 * Dm, kRoundOffRelTol * Dm);
  // Open coil: pitch L/n = 1.37 mm > d0, closed at n d0 = 13.5 mm.
  EXPECT_NEAR(tca.closed_elongation_m(), n * 0.74e-3 - 0.025, kRoundOffRelTol * 0.025);
  EXPECT_TRUE(tca.has_coil_contact());
}

TEST(MeasuredFiber, PaperConversionsStayWithoutIt) {
  // Without fiber_diameter_m: d0 = 2 D L/l, Dm = D/2, closed at L for an extension TCA and no
  // contact for a contraction TCA, exactly as before.
  const Tca ext(three_thread(Kind::kExtension), nylon_monocoil());
  EXPECT_FALSE(ext.has_measured_fiber_diameter());
  EXPECT_EQ(ext.initial_fiber_diameter_m(), 2.0 * 0.002 * 0.110 / 0.497);
  EXPECT_EQ(ext.mean_coil_diameter_m(), 0.001);
  EXPECT_EQ(ext.closed_elongation_m(), 0.0);
  EXPECT_TRUE(ext.has_coil_contact());
  const Tca con(three_thread(Kind::kContraction), nylon_monocoil());
  EXPECT_FALSE(con.has_coil_contact());
  // The measured fiber changes the spring: f11 ~ l^3/(n^2 d^4) with the paper's d0 = 1.22 mm
  // and this coil's 0.74 mm differ by far more than any tolerance.
  Parameters paper = open_monocoil();
  paper.fiber_diameter_m.reset();
  const Tca nominal(paper, nylon_monocoil()), measured(open_monocoil(), nylon_monocoil());
  const double t = K(25.0);
  EXPECT_GT(nominal.tension(1e-3, t).tension_N, 3.0 * measured.tension(1e-3, t).tension_N);
}

TEST(MeasuredFiber, OpenCoilShortensUntilItsCoilsTouch) {
  for (const Kind kind : {Kind::kContraction, Kind::kExtension}) {
    SCOPED_TRACE(to_string(kind));
    const Tca tca(open_monocoil(kind), nylon_monocoil());
    const double dc = tca.closed_elongation_m();
    const double t = K(25.0);
    // A compression smaller than the closed force leaves the coil open below L.
    const double fc = tca.closed_force(t);
    ASSERT_LT(fc, 0.0);
    const ElongationState open = tca.elongation(0.5 * fc, t);
    EXPECT_FALSE(open.coils_closed);
    EXPECT_LT(open.elongation_m, 0.0);
    EXPECT_GT(open.elongation_m, dc);
    // A larger compression holds it at its closed length n d0.
    const ElongationState closed = tca.elongation(2.0 * fc, t);
    EXPECT_TRUE(closed.coils_closed);
    EXPECT_EQ(closed.elongation_m, dc);
    EXPECT_NEAR(std::sin(closed.pitch_angle_rad),
                tca.coil_count() * 0.74e-3 / tca.parameters().fiber_length_m, kRoundOffRelTol);
    EXPECT_TRUE(tca.tension(dc - 1e-6, t).below_closed_length);
    EXPECT_FALSE(tca.tension(dc + 1e-6, t).below_closed_length);
    const std::vector<Segment> one{{1.0, t}};
    EXPECT_EQ(contact_residual(tca, 2.0 * fc, dc, one).phi_N, 0.0);
    const std::vector<SegmentContact> sc = segment_contacts(tca, 2.0 * fc, one);
    EXPECT_TRUE(sc[0].coils_closed);
    EXPECT_NEAR(sc[0].contact_force_N, -fc, kRoundOffRelTol * std::abs(fc));
  }
}

TEST(MeasuredFiber, OnsetIsWhereTheClosedForceFallsToTheLoad) {
  // Extension TCA (s = +1): heating pushes the coils apart, F_c(T) falls.
  const Tca tca(open_monocoil(Kind::kExtension), nylon_monocoil());
  const double load = tca.closed_force(K(90.0));
  const auto onset = tca.onset_temperature(load, K(25.0), K(160.0));
  ASSERT_TRUE(onset.has_value());
  EXPECT_NEAR(*onset, K(90.0), 1e-8);
  // The paper's contraction TCA has no closed length.
  Parameters paper = open_monocoil();
  paper.fiber_diameter_m.reset();
  EXPECT_THROW((void)Tca(paper, nylon_monocoil()).onset_temperature(0.0, K(25.0), K(90.0)),
               InputError);
}

TEST(MeasuredFiber, ContactResidualDerivativesMatchCentralDifferencesOnEveryBranch) {
  const Tca tca(open_monocoil(Kind::kContraction), nylon_monocoil());
  const double dc = tca.closed_elongation_m();
  const double t = K(90.0);
  const double fc = tca.closed_force(t);
  const std::vector<testing::ContactCase> cases = {
      {"open", 0.5, 0.004, {{1.0, t}}},
      {"open below L", 0.5 * fc, 0.6 * dc, {{1.0, t}}},
      {"closed", fc - 0.05, dc + 1e-5, {{1.0, t}}},
      {"below closed length", fc + 0.02, dc - 2e-4, {{1.0, t}}},
      {"segments, both open", 0.2, 0.003, {{0.4, K(60.0)}, {0.6, K(120.0)}}},
      {"segments, one closed",
       0.5 * (tca.closed_force(K(40.0)) + tca.closed_force(K(140.0))),
       0.5 * dc,
       {{0.5, K(40.0)}, {0.5, K(140.0)}}},
  };
  testing::expect_contact_residual_derivatives(tca, cases, kFdRelTol);
}

TEST(MeasuredFiber, TensionTangentsMatchFiniteDifferences) {
  const Tca tca(open_monocoil(), nylon_monocoil());
  for (const double delta : {-0.005, 0.0, 0.004, 0.008}) {
    for (const double t_degC : {25.0, 120.0}) {
      const double t = K(t_degC);
      const TensionState st = tca.tension(delta, t);
      const double fd_d =
          central_difference([&](double x) { return tca.tension(x, t).tension_N; }, delta, 1e-8);
      const double fd_t =
          central_difference([&](double x) { return tca.tension(delta, x).tension_N; }, t, 1e-3);
      EXPECT_NEAR(st.dF_ddelta_N_m, fd_d, kFdRelTol * std::abs(fd_d)) << delta << " " << t_degC;
      EXPECT_NEAR(st.dF_dT_N_K, fd_t, kFdRelTol * std::abs(fd_t)) << delta << " " << t_degC;
    }
  }
}

TEST(MeasuredFiber, ImpossibleGeometryIsRefusedNamingTheKey) {
  Parameters p = open_monocoil();
  p.fiber_diameter_m = 1.2e-3;  // D = 2.372 mm: D - 2 d0 < 0
  EXPECT_NE(input_error_message(p).find("fiber_diameter_m = 0.0012 must be < outer_diameter_m/2"),
            std::string::npos)
      << input_error_message(p);
  p = open_monocoil();
  p.fiber_diameter_m = 0.0;
  EXPECT_EQ(input_error_message(p), "fiber_diameter_m = 0 must be > 0");
  p = open_monocoil();
  p.coiled_length_m = 0.012;  // 18 coils of 0.74 mm need 13.4 mm: they would overlap
  p.fiber_length_m = fiber_length_from_coil_count(0.012, 1.632e-3, 18.3);
  EXPECT_NE(input_error_message(p).find("the coils would overlap"), std::string::npos)
      << input_error_message(p);
  EXPECT_EQ(input_error_message(p).rfind("fiber_diameter_m = 0.00074", 0), 0u);
  p = open_monocoil();
  p.twist_turns = 200.0;  // l/N = 0.49 mm < d0
  EXPECT_NE(input_error_message(p).find("twist_turns = 200 must be <= fiber_length_m/"),
            std::string::npos)
      << input_error_message(p);
  p = open_monocoil();
  p.fiber_length_m = 0.0252;  // 0.62 coils
  EXPECT_NE(input_error_message(p).find("must give n >= 1"), std::string::npos)
      << input_error_message(p);
  // A coil wound closed within the measurement tolerance is accepted and sits closed at L.
  p = open_monocoil();
  p.coiled_length_m = 18.3 * 0.74e-3 * (1.0 - 0.5 * kGeometryRelativeTolerance);
  p.fiber_length_m = fiber_length_from_coil_count(p.coiled_length_m, 1.632e-3, 18.3);
  const Tca closed(p, nylon_monocoil());
  EXPECT_EQ(closed.closed_elongation_m(), 0.0);
}

}  // namespace
}  // namespace tcasim::tca
