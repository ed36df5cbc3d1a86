// Unit tests of the TCA model ([Pawlowski2019] Section II; docs/conventions.md "TCA model
// ([Pawlowski2019] Section II)").
#include "tca/tca.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "contact_checks.hpp"
#include "tca/curve.hpp"
#include "test_materials.hpp"

namespace tcasim::tca {
namespace {

using testing::four_thread;
using testing::K;
using testing::softening;
using testing::sun2022;
using testing::three_thread;
using units::kPi;

/// Central difference of a scalar function.
double central_difference(const std::function<double(double)>& f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

/// Central differences with steps 1e-6 m / 1e-3 K on laws varying over ~0.1 m / ~100 K:
/// truncation ~(h/scale)^2 <= 1e-10, round-off ~1e-11; 1e-6 leaves a wide margin yet
/// catches any missing term (the smallest, the E_T part of df11/dT, is ~1e-3 relative).
constexpr double kFdRelTol = 1e-6;
/// Agreement of two evaluations of the same closed-form quantity (round-off only).
constexpr double kRoundOffRelTol = 1e-12;
/// Root-finder results: elongation tolerance 1e-16 m plus 4 eps relative.
constexpr double kRootRelTol = 1e-10;

void expect_rel_near(double actual, double expected, double rel_tol, const std::string& what) {
  EXPECT_NEAR(actual, expected, rel_tol * std::max(std::abs(expected), 1e-300)) << what;
}

// ---------------------------------------------------------------------------------------
// Eq. (3) and Eq. (4) from the complementary energy of a helical twisted fiber.
//
// Coil radius R = l cos(alpha)/(2 pi n) (a coil of fiber length l/n projects 2 pi R onto
// the coil plane). An axial force F at the coil axis loads each fiber section with the
// torsion F R cos(alpha), bending F R sin(alpha), shear F cos(alpha) and tension
// F sin(alpha); the active untwisting torque tau adds to the torsion. With J = pi d^4/32,
// I = pi d^4/64, A = pi d^2/4 and no shear correction factor:
//   U*(F, tau) = l/2 [ (F R cos a + tau)^2/(G J) + (F R sin a)^2/(E I)
//                      + (F cos a)^2/(G A) + (F sin a)^2/(E A) ].
// d2U/dF2 reproduces Eq. (3) term by term (the first bracket from torsion and bending, the
// second from shear and tension); d2U/dF dtau = l R cos(a)/(G J) = 16 l^2 cos^2/(pi^2 n
// d^4 G), twice the printed Eq. (4): f12_form castigliano = 16 matches, paper = 8 is half.
// ---------------------------------------------------------------------------------------
double complementary_energy(const Tca& tca, double alpha, double t_K, double F, double tau) {
  const MaterialState m = tca.material().at(t_K);
  const double l = tca.parameters().fiber_length_m;
  const double d = tca.initial_fiber_diameter_m() * m.diameter_ratio;
  const double J = kPi * std::pow(d, 4) / 32.0, I = kPi * std::pow(d, 4) / 64.0;
  const double A = kPi * d * d / 4.0;
  const double R = l * std::cos(alpha) / (2.0 * kPi * tca.coil_count());
  const double c = std::cos(alpha), s = std::sin(alpha);
  const double G = m.shear_modulus_Pa, E = m.youngs_modulus_Pa;
  return 0.5 * l *
         (std::pow(F * R * c + tau, 2) / (G * J) + std::pow(F * R * s, 2) / (E * I) +
          std::pow(F * c, 2) / (G * A) + std::pow(F * s, 2) / (E * A));
}

TEST(TcaEnergy, ComplementaryEnergyGivesEq3AndTwiceEq4) {
  // U* is exactly quadratic, so second differences have no truncation error; round-off
  // with these steps is ~eps U/h^2 ~ 1e-12 relative.
  constexpr double kEnergyRelTol = 1e-7;
  const double hF = 0.05, htau = 2e-4;  // [N], [N m]
  const double F0 = 0.03, tau0 = 1e-4;
  for (const Material& mat : {sun2022(), softening()}) {
    const Tca cast(three_thread(Kind::kExtension, F12Form::kCastigliano), mat);
    const Tca paper(three_thread(Kind::kExtension, F12Form::kPaper), mat);
    for (const double alpha_deg : {5.0, 12.79, 30.0, 60.0}) {
      for (const double t_degC : {25.0, 90.0, 160.0}) {
        const double a = units::deg_to_rad(alpha_deg), t = K(t_degC);
        const auto U = [&](double F, double tau) {
          return complementary_energy(cast, a, t, F, tau);
        };
        const double f11 = (U(F0 + hF, tau0) - 2.0 * U(F0, tau0) + U(F0 - hF, tau0)) / (hF * hF);
        const double f12 = (U(F0 + hF, tau0 + htau) - U(F0 + hF, tau0 - htau) -
                            U(F0 - hF, tau0 + htau) + U(F0 - hF, tau0 - htau)) /
                           (4.0 * hF * htau);
        const Coefficients cc = cast.coefficients(a, t), cp = paper.coefficients(a, t);
        const std::string at = mat.name + " alpha " + std::to_string(alpha_deg) + " deg, T " +
                               std::to_string(t_degC) + " degC";
        expect_rel_near(cc.f11_m_N, f11, kEnergyRelTol, "f11 castigliano, " + at);
        expect_rel_near(cp.f11_m_N, f11, kEnergyRelTol, "f11 paper, " + at);
        expect_rel_near(cc.f12_1_N, f12, kEnergyRelTol, "f12 castigliano (16), " + at);
        expect_rel_near(cp.f12_1_N, 0.5 * f12, kEnergyRelTol, "f12 paper (8) = half, " + at);
      }
    }
  }
}

TEST(TcaConversions, Fig5GeometryGivesPhysicsNotesValues) {
  // docs/conventions.md "TCA data of the paper's experiments" quotes alpha0, n and d0 to 3-4
  // digits.
  const Tca t3(three_thread(), sun2022()), t4(four_thread(), sun2022());
  EXPECT_NEAR(units::rad_to_deg(t3.initial_pitch_angle_rad()), 12.79, 0.005);
  EXPECT_NEAR(t3.coil_count(), 154.3, 0.05);
  EXPECT_NEAR(t3.initial_fiber_diameter_m(), 0.885e-3, 0.0005e-3);
  EXPECT_NEAR(t3.initial_twist_rad(), 2.0 * kPi * 300.0, 1e-9);
  EXPECT_NEAR(units::rad_to_deg(t4.initial_pitch_angle_rad()), 13.51, 0.005);
  EXPECT_NEAR(t4.coil_count(), 136.9, 0.05);
  EXPECT_NEAR(t4.initial_fiber_diameter_m(), 0.995e-3, 0.0005e-3);
  EXPECT_DOUBLE_EQ(t3.chirality(), 1.0);
  EXPECT_DOUBLE_EQ(Tca(three_thread(Kind::kContraction), sun2022()).chirality(), -1.0);
  EXPECT_NEAR(fiber_length_from_pitch(0.110, t3.initial_pitch_angle_rad()), 0.497, 1e-12);
}

TEST(TcaConversions, TensionLawEqualsEq6WithPrintedCoefficients) {
  // tension() uses the closed form f12 tau = k l phi0 cos^2 (1 - 1/r)/(32 pi n); this
  // checks it against Eqs. (1), (3), (4) evaluated literally.
  for (const Kind kind : {Kind::kExtension, Kind::kContraction}) {
    for (const F12Form form : {F12Form::kPaper, F12Form::kCastigliano}) {
      const Tca tca(three_thread(kind, form), softening());
      for (const double delta : {-0.01, 0.0, 0.02, 0.1}) {
        for (const double t_degC : {25.0, 100.0, 170.0}) {
          const TensionState st = tca.tension(delta, K(t_degC));
          const Coefficients c = tca.coefficients(st.pitch_angle_rad, K(t_degC));
          // [Pawlowski2019] Eq. (6) with chirality.
          const double expected = (delta - tca.chirality() * c.f12_1_N * c.tau_Nm) / c.f11_m_N;
          EXPECT_NEAR(st.tension_N, expected, kRoundOffRelTol * 1e3 * (std::abs(expected) + 1.0))
              << to_string(kind) << " " << to_string(form) << " delta " << delta;
          EXPECT_NEAR(std::sin(st.pitch_angle_rad),
                      std::sin(tca.initial_pitch_angle_rad()) + delta / 0.497, 1e-15);
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------
// Tangents against finite differences.
// ---------------------------------------------------------------------------------------
TEST(TcaTangents, MaterialDerivativesMatchFiniteDifferences) {
  const double h = 1e-3;  // [K]
  for (const Material& m : {sun2022(), softening()}) {
    for (const double t_degC : {30.0, 80.0, 155.0}) {
      const double t = K(t_degC);
      const MaterialState s = m.at(t);
      expect_rel_near(
          s.dE_dT_Pa_K + 1.0,
          central_difference([&](double x) { return m.at(x).youngs_modulus_Pa; }, t, h) + 1.0,
          kFdRelTol, m.name + " dE/dT");
      expect_rel_near(
          s.dG_dT_Pa_K + 1.0,
          central_difference([&](double x) { return m.at(x).shear_modulus_Pa; }, t, h) + 1.0,
          kFdRelTol, m.name + " dG/dT");
      expect_rel_near(s.dratio_dT_1_K,
                      central_difference([&](double x) { return m.at(x).diameter_ratio; }, t, h),
                      kFdRelTol, m.name + " d ratio/dT");
    }
  }
  // Reference temperature gives d = d0 for both diameter laws.
  EXPECT_NEAR(sun2022().at(K(25.0)).diameter_ratio, 1.0, 1e-15);
  EXPECT_NEAR(softening().at(K(25.0)).diameter_ratio, 1.0, 1e-15);
}

TEST(TcaTangents, TensionTangentsMatchFiniteDifferences) {
  const double h_delta = 1e-6, h_t = 1e-3;  // [m], [K]
  for (const Kind kind : {Kind::kExtension, Kind::kContraction}) {
    for (const F12Form form : {F12Form::kPaper, F12Form::kCastigliano}) {
      for (const Material& mat : {sun2022(), softening()}) {
        const Tca tca(four_thread(kind, form), mat);
        for (const double delta : {-0.02, 0.0, 0.005, 0.05, 0.2}) {
          for (const double t_degC : {30.0, 95.0, 150.0}) {
            const double t = K(t_degC);
            const TensionState st = tca.tension(delta, t);
            const double fd_delta = central_difference(
                [&](double x) { return tca.tension(x, t).tension_N; }, delta, h_delta);
            const double fd_t = central_difference(
                [&](double x) { return tca.tension(delta, x).tension_N; }, t, h_t);
            const std::string at = std::string(to_string(kind)) + "/" + to_string(form) + "/" +
                                   mat.name + " delta " + std::to_string(delta) + " T " +
                                   std::to_string(t_degC);
            expect_rel_near(st.dF_ddelta_N_m, fd_delta, kFdRelTol, "dF/ddelta " + at);
            expect_rel_near(st.dF_dT_N_K, fd_t, kFdRelTol, "dF/dT " + at);
          }
        }
      }
    }
  }
}

TEST(TcaTangents, SeriesTangentsMatchFiniteDifferences) {
  const double h_delta = 1e-6, h_t = 1e-3;
  const Tca tca(three_thread(), softening());
  const std::vector<Segment> segs = {{0.2, K(40.0)}, {0.5, K(120.0)}, {0.3, K(80.0)}};
  for (const double delta : {0.01, 0.06}) {
    const SeriesTensionState st = series_tension(tca, delta, segs);
    const double fd = central_difference(
        [&](double x) { return series_tension(tca, x, segs).tension_N; }, delta, h_delta);
    expect_rel_near(st.dF_ddelta_N_m, fd, kFdRelTol, "series dF/ddelta");
    ASSERT_EQ(st.dF_dT_N_K.size(), segs.size());
    for (std::size_t k = 0; k < segs.size(); ++k) {
      const double fdk = central_difference(
          [&](double x) {
            auto s = segs;
            s[k].temperature_K = x;
            return series_tension(tca, delta, s).tension_N;
          },
          segs[k].temperature_K, h_t);
      expect_rel_near(st.dF_dT_N_K[k], fdk, kFdRelTol, "series dF/dT_" + std::to_string(k));
    }
  }
}

// ---------------------------------------------------------------------------------------
// Signs, inverses, closed coils.
// ---------------------------------------------------------------------------------------
TEST(TcaSigns, ExtensionTcaExtendsWhenHeated) {
  const Tca tca(three_thread(Kind::kExtension), sun2022());
  EXPECT_DOUBLE_EQ(tca.free_stroke(K(25.0)), 0.0);  // no expansion at T_ref, no load
  EXPECT_GT(tca.free_stroke(K(100.0)), 0.0);
  EXPECT_GT(tca.free_stroke(K(160.0)), tca.free_stroke(K(100.0)));
  EXPECT_LT(tca.blocked_force(K(100.0)), 0.0);  // held closed, it pushes
  EXPECT_GT(tca.tension(0.01, K(25.0)).dF_ddelta_N_m, 0.0);
  EXPECT_LT(tca.tension(0.01, K(100.0)).dF_dT_N_K, 0.0);
}

TEST(TcaSigns, ContractionTcaShortensWhenHeated) {
  // Contraction TCAs have no closure in tcasim: coils assumed open (prestretched).
  const Tca tca(three_thread(Kind::kContraction), sun2022());
  const double F = 0.2;  // [N] prestretching tension
  const double d25 = tca.elongation(F, K(25.0)).elongation_m;
  const double d100 = tca.elongation(F, K(100.0)).elongation_m;
  EXPECT_GT(d25, 0.0);
  EXPECT_LT(d100, d25);
  EXPECT_LT(tca.free_stroke(K(120.0)), 0.0);  // shortens below L when free
  EXPECT_FALSE(tca.elongation(0.0, K(120.0)).coils_closed);
  EXPECT_GT(tca.tension(0.01, K(100.0)).dF_dT_N_K, 0.0);  // heating pulls harder
}

TEST(TcaInverse, TensionOfElongationRoundTrips) {
  for (const Kind kind : {Kind::kExtension, Kind::kContraction}) {
    const Tca tca(four_thread(kind, F12Form::kPaper), softening());
    for (const double F : {-0.05, 0.0, 0.1, 1.0}) {
      for (const double t_degC : {25.0, 70.0, 160.0}) {
        const ElongationState e = tca.free_coil_elongation(F, K(t_degC));
        const TensionState st = tca.tension(e.elongation_m, K(t_degC));
        EXPECT_NEAR(st.tension_N, F, kRootRelTol * (std::abs(F) + 1e-2)) << F << " " << t_degC;
        EXPECT_NEAR(st.pitch_angle_rad, e.pitch_angle_rad, 1e-12);
        if (kind == Kind::kExtension && e.elongation_m >= 0.0) {
          EXPECT_EQ(tca.elongation(F, K(t_degC)).elongation_m, e.elongation_m);
        }
      }
    }
  }
}

TEST(TcaInverse, TemperatureForTensionInvertsTension) {
  const Tca tca(three_thread(), softening());
  const double delta = 0.02, t_true = K(117.0);
  const double F = tca.tension(delta, t_true).tension_N;
  EXPECT_NEAR(tca.temperature_for_tension(F, delta, K(20.0), K(170.0)), t_true, 1e-8);
  // A tension not reachable in the range: DomainError naming the range.
  try {
    (void)tca.temperature_for_tension(F, delta, K(20.0), K(60.0));
    ADD_FAILURE() << "expected DomainError";
  } catch (const DomainError& e) {
    EXPECT_NE(std::string(e.what()).find("[20 degC, 60 degC]"), std::string::npos) << e.what();
  }
}

TEST(TcaClosedCoils, ZeroElongationBelowOnsetThenMonotone) {
  const Tca tca(three_thread(), sun2022());
  const double F = hanging_load_tension_N(units::g_to_kg(7.5));
  const auto onset = tca.onset_temperature(F, K(25.0), K(160.0));
  ASSERT_TRUE(onset.has_value());
  EXPECT_GT(*onset, K(25.0));
  // Just below the onset closed, just above open (the onset is a root of the blocked force).
  const ElongationState below = tca.elongation(F, *onset - 1e-3);
  EXPECT_TRUE(below.coils_closed);
  EXPECT_EQ(below.elongation_m, 0.0);
  EXPECT_GT(tca.elongation(F, *onset + 1e-3).elongation_m, 0.0);
  EXPECT_NEAR(tca.blocked_force(*onset), F, 1e-12);
  double previous = 0.0;
  for (double t_degC = 25.0; t_degC <= 160.0; t_degC += 1.0) {
    const ElongationState e = tca.elongation(F, K(t_degC));
    if (K(t_degC) < *onset) {
      EXPECT_EQ(e.elongation_m, 0.0) << t_degC;
      EXPECT_TRUE(e.coils_closed);
    } else {
      EXPECT_GT(e.elongation_m, previous) << t_degC;  // strictly increasing once open
    }
    previous = e.elongation_m;
  }
}

TEST(TcaClosedCoils, HeavierLoadGivesLaterOnset) {
  for (const F12Form form : {F12Form::kPaper, F12Form::kCastigliano}) {
    const Tca tca(four_thread(Kind::kExtension, form), sun2022());
    const auto light =
        tca.onset_temperature(hanging_load_tension_N(units::g_to_kg(7.5)), K(25.0), K(160.0));
    const auto heavy =
        tca.onset_temperature(hanging_load_tension_N(units::g_to_kg(15.0)), K(25.0), K(160.0));
    ASSERT_TRUE(light && heavy);
    EXPECT_GT(*heavy, *light);
  }
  // A load beyond the blocked force at 160 degC keeps the coils closed.
  const Tca tca(three_thread(), sun2022());
  EXPECT_FALSE(tca.onset_temperature(2.0 * tca.blocked_force(K(160.0)), K(25.0), K(160.0)));
  // A pulling load opens the coils at once.
  EXPECT_EQ(*tca.onset_temperature(0.01, K(25.0), K(160.0)), K(25.0));
  EXPECT_THROW((void)Tca(three_thread(Kind::kContraction), sun2022())
                   .onset_temperature(-0.1, K(25.0), K(160.0)),
               InputError);
}

// ---------------------------------------------------------------------------------------
// Segments in series.
// ---------------------------------------------------------------------------------------
TEST(TcaSeries, EqualTemperaturesEqualTheSingleTca) {
  const Tca tca(three_thread(), softening());
  const double t = K(110.0);
  const std::vector<Segment> segs = {{0.3, t}, {0.7, t}};
  for (const double delta : {0.005, 0.04}) {
    const SeriesTensionState s = series_tension(tca, delta, segs);
    const TensionState one = tca.tension(delta, t);
    expect_rel_near(s.tension_N, one.tension_N, kRootRelTol, "series tension");
    expect_rel_near(s.dF_ddelta_N_m, one.dF_ddelta_N_m, kRootRelTol, "series dF/ddelta");
    expect_rel_near(s.dF_dT_N_K[0] + s.dF_dT_N_K[1], one.dF_dT_N_K, 1e-9, "sum of dF/dT_k");
  }
  for (const double F : {-0.07, 0.0, 0.3}) {
    expect_rel_near(series_elongation(tca, F, segs) + 1.0, tca.elongation(F, t).elongation_m + 1.0,
                    kRoundOffRelTol, "series elongation");
  }
}

TEST(TcaSeries, SeriesTensionInvertsSeriesElongation) {
  const Tca tca(four_thread(), sun2022());
  const std::vector<Segment> segs = {{0.25, K(150.0)}, {0.75, K(50.0)}};
  for (const double F : {0.05, 0.5}) {  // pulling: every segment open
    const double delta = series_elongation(tca, F, segs);
    EXPECT_NEAR(series_tension(tca, delta, segs).tension_N, F, kRootRelTol * std::abs(F));
  }
  EXPECT_THROW((void)series_elongation(tca, 0.1, {{0.5, K(50.0)}, {0.4, K(60.0)}}), InputError);
  EXPECT_THROW((void)series_tension(tca, 0.01, {}), InputError);
  EXPECT_THROW((void)series_tension(tca, 0.01, {{1.2, K(50.0)}}), InputError);
}

// ---------------------------------------------------------------------------------------
// Rejections.
// ---------------------------------------------------------------------------------------
std::string input_error_message(const Parameters& p, const Material& m) {
  try {
    (void)Tca(p, m);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

/// The contact residual's open, closed and segmented branches at points away from their
/// kinks, each analytic derivative against central differences.
TEST(TcaContact, ContactResidualDerivativesMatchCentralDifferencesOnEveryBranch) {
  const Tca tca(three_thread(Kind::kExtension), softening());
  const double t = K(90.0);
  const double fb = tca.blocked_force(t);
  const std::vector<testing::ContactCase> cases = {
      {"open", fb + 0.05, tca.free_coil_elongation(fb + 0.05, t).elongation_m, {{1.0, t}}},
      {"open, off the law", fb + 0.05, 0.004, {{1.0, t}}},
      {"closed", fb - 0.05, 1e-4, {{1.0, t}}},
      {"below closed length", fb + 0.02, -2e-4, {{1.0, t}}},
      {"segments, both open", 0.02, 0.003, {{0.4, K(60.0)}, {0.6, K(120.0)}}},
      {"segments, one closed",
       0.5 * (tca.blocked_force(K(40.0)) + tca.blocked_force(K(140.0))),
       0.002,
       {{0.5, K(40.0)}, {0.5, K(140.0)}}},
  };
  testing::expect_contact_residual_derivatives(tca, cases, kFdRelTol);
}

TEST(TcaContact, ResidualVanishesExactlyOnTheOpenLawAndOnTheClosedStrut) {
  const Tca tca(three_thread(Kind::kExtension), sun2022());
  const double t = K(90.0);
  const double fb = tca.blocked_force(t);
  const std::vector<Segment> one{{1.0, t}};
  // Open: F = F_free(delta), delta > 0. The one-segment branch is T - F_free (old TCA rows).
  const double d = 0.003;
  const double F = tca.tension(d, t).tension_N;
  EXPECT_EQ(contact_residual(tca, F, d, one).phi_N, 0.0);
  EXPECT_EQ(contact_residual(tca, F, d, one).dphi_dF, 1.0);
  // Closed: delta = 0 with any tension below the blocked force (contact force c = F_b - F).
  for (const double c : {1e-6, 0.1, 10.0}) {
    EXPECT_EQ(contact_residual(tca, fb - c, 0.0, one).phi_N, 0.0);
    const std::vector<SegmentContact> sc = segment_contacts(tca, fb - c, one);
    EXPECT_TRUE(sc[0].coils_closed);
    EXPECT_NEAR(sc[0].contact_force_N, c, 1e-12 * std::max(1.0, c));
  }
  // Not a state: shorter than closed, or closed with a tension above the blocked force.
  EXPECT_GT(contact_residual(tca, fb - 0.1, -1e-4, one).phi_N, 0.0);
  EXPECT_GT(contact_residual(tca, fb + 0.1, 0.0, one).phi_N, 0.0);
  // A contraction TCA has no coil contact: the free-coil law below L too.
  const Tca contraction(three_thread(Kind::kContraction), sun2022());
  const double dc = -0.002;
  EXPECT_EQ(contact_residual(contraction, contraction.tension(dc, t).tension_N, dc, one).phi_N,
            0.0);
  EXPECT_FALSE(segment_contacts(contraction, -10.0, one)[0].coils_closed);
}

TEST(TcaContact, SegmentedResidualVanishesWhereOneSegmentIsClosedAndTheOtherCarriesTheStroke) {
  const Tca tca(three_thread(Kind::kExtension), sun2022());
  const std::vector<Segment> segs{{0.5, K(40.0)}, {0.5, K(140.0)}};
  const double F = 0.5 * (tca.blocked_force(K(40.0)) + tca.blocked_force(K(140.0)));
  // Segment 0 closed (F below its blocked force), segment 1 open at half the TCA's length.
  const double delta = 0.5 * tca.free_coil_elongation(F, K(140.0)).elongation_m;
  ASSERT_GT(delta, 0.0);
  EXPECT_NEAR(contact_residual(tca, F, delta, segs).phi_N, 0.0,
              kRootRelTol * tca.contact_stiffness_N_m() * delta);
  const std::vector<SegmentContact> sc = segment_contacts(tca, F, segs);
  EXPECT_TRUE(sc[0].coils_closed);
  EXPECT_FALSE(sc[1].coils_closed);
  // The same total elongation without contact (series free-coil law) needs another tension.
  EXPECT_GT(std::abs(series_tension(tca, delta, segs).tension_N - F), 1e-3 * std::abs(F));
}

TEST(TcaRejects, InvalidParametersNameTheKey) {
  Parameters p = three_thread();
  p.coiled_length_m = 0.5;
  p.fiber_length_m = 0.11;
  EXPECT_EQ(input_error_message(p, sun2022()),
            "coiled_length_m = 0.5 must be < fiber_length_m = 0.11");
  p = three_thread();
  p.coiled_length_m = 0.0;
  EXPECT_EQ(input_error_message(p, sun2022()), "coiled_length_m = 0 must be > 0");
  p = three_thread();
  p.coiled_length_m = 0.3;  // L/l > 1/2: d0 = 2 D L/l > D
  EXPECT_NE(input_error_message(p, sun2022()).find("fiber diameter d0"), std::string::npos);
  p = three_thread();
  p.outer_diameter_m = -1e-3;
  EXPECT_EQ(input_error_message(p, sun2022()), "outer_diameter_m = -0.001 must be > 0");
  p = three_thread();
  p.outer_diameter_m = 0.5;  // n = 0.62 coils
  EXPECT_NE(input_error_message(p, sun2022()).find("n >= 1"), std::string::npos);
  p = three_thread();
  p.twist_turns = 0.0;
  EXPECT_EQ(input_error_message(p, sun2022()), "twist_turns = 0 must be > 0");
  Material bad = sun2022();
  bad.shear_modulus_Pa.coefficients = {-1.0};
  EXPECT_NE(input_error_message(three_thread(), bad).find("material = silver-nylon-sun2022"),
            std::string::npos);
}

TEST(TcaRejects, OutOfDomainStatesThrowDomainError) {
  const Tca tca(three_thread(), sun2022());
  EXPECT_THROW((void)tca.elongation(0.0, K(200.0)), DomainError);  // above valid range
  EXPECT_THROW((void)tca.tension(0.0, K(10.0)), DomainError);      // below valid range
  EXPECT_THROW((void)tca.tension(0.5, K(50.0)), DomainError);      // sin(alpha) > 1
  EXPECT_THROW((void)tca.pitch_angle(-0.2), DomainError);          // sin(alpha) < 0
  Material soft = softening();
  soft.youngs_modulus_Pa.coefficients = {1e9, -1e7};  // E = 0 at 100 degC
  const Tca weak(three_thread(), soft);
  EXPECT_THROW((void)weak.tension(0.0, K(120.0)), DomainError);
  EXPECT_NO_THROW((void)weak.tension(0.0, K(90.0)));
}

TEST(TcaCurve, HangingMassCompressesTheTca) {
  EXPECT_DOUBLE_EQ(hanging_load_tension_N(0.010), -0.0980665);
}

}  // namespace
}  // namespace tcasim::tca
