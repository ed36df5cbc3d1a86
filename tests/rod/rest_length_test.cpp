// Rest length and regularity of the string paths (docs/scenario-format.md, "Rest length and
// regularity"): the reference path length whatever the routing and precurvature, a folded
// path refused, the TCA's coiled length matched to the path or given a pre_elongation_m.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>

#include "common/error.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "support/input_error.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Closed forms and the round-off of a quadrature refined to round-off (relative).
constexpr double kRoundOff = 1e-13;

/// A 40 mm EcoFlex rod with one extension TCA 3 mm off-axis; the TCA's coiled length is
/// set per test.
json scenario(double curvature_y_1_m, double coiled_length_m) {
  json doc = json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "rest-length-test",
    "body": {"length_m": 0.040, "section": {"shape": "circle", "diameter_m": 0.008},
             "material": {"youngs_modulus_Pa": 37.8e3, "poisson_ratio": 0.5}},
    "tcas": {"t": {"kind": "extension", "pitch_angle_deg": 15, "outer_diameter_m": 0.0017,
                   "twist_turns": 76.4,
                   "material": {"source": "test values", "reference_temperature_degC": 25,
                                "youngs_modulus_Pa": 1.2e9, "shear_modulus_Pa": 2.2e8,
                                "diameter": {"linear_expansion_1_K": 1.0e-4},
                                "valid_range_degC": [20, 200]}}},
    "actuators": [{"name": "tca", "routing": {"type": "straight", "offset_m": [0.003, 0.0]},
                   "drive": {"type": "tca", "tca": "t", "temperature_degC": 90}}]
  })");
  doc["body"]["reference_curvature_1_m"] = {0.0, curvature_y_1_m, 0.0};
  doc["tcas"]["t"]["coiled_length_m"] = coiled_length_m;
  return doc;
}

/// Expects parse_scenario(doc) to throw InputError with this key and rule fragment.
void expect_refused(const json& doc, const std::string& key, const std::string& rule) {
  test_support::expect_input_error([&] { (void)parse_scenario(doc); }, key, rule);
}

TEST(ReferencePath, StraightStringOnAPrecurvedBodyHasTheClosedFormLength) {
  // q* = e3 + omega* x r = (-w3 y, w3 x, 1 + w1 y - w2 x), constant along s.
  Routing r;
  r.offset_m = {0.002, -0.001};
  const Eigen::Vector3d w(10.0, -5.0, 2.0);
  const double expected =
      0.05 * Eigen::Vector3d(-2.0 * -0.001, 2.0 * 0.002, 1.0 + 10.0 * -0.001 + 5.0 * 0.002).norm();
  const ReferencePath p = reference_path(r, w, 0.05);
  EXPECT_NEAR(p.length_m / expected, 1.0, kRoundOff);
  EXPECT_NEAR(p.min_axial, 1.0 + 10.0 * -0.001 + 5.0 * 0.002, kRoundOff);
}

TEST(ReferencePath, HelixOnAPrecurvedBodyMatchesAFineSimpsonRuleOverManyTurns) {
  Routing r;
  r.type = Routing::Type::kHelix;
  r.radius_m = 0.003;
  r.phase_rad = 0.3;
  r.turns_per_m = -137.0;  // 6.85 turns on 50 mm, left-handed: whole periods and a remainder
  const Eigen::Vector3d w(60.0, 80.0, 3.0);  // |omega*_perp| R = 0.3
  const double L = 0.05;
  // Composite Simpson on 200000 intervals of |e3 + omega* x r + r'| (error ~ h^4, far
  // below the tolerance), with the routing's own r and r'.
  constexpr int kIntervals = 200000;
  const double h = L / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double s = i * h;
    const double f = (Eigen::Vector3d::UnitZ() + w.cross(r.r(s)) + r.dr(s)).norm();
    sum += f * ((i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  const ReferencePath p = reference_path(r, w, L);
  EXPECT_NEAR(p.length_m / (sum * h / 3.0), 1.0, kRoundOff);
  // The helix sweeps every direction: the smallest axial component is 1 - R |omega*_perp|.
  EXPECT_NEAR(p.min_axial, 1.0 - 0.3, kRoundOff);
}

TEST(ReferencePath, HelixWithoutBendingPrecurvatureKeepsItsClosedForm) {
  Routing r;
  r.type = Routing::Type::kHelix;
  r.radius_m = 0.003;
  r.turns_per_m = 25.0;
  const double c = 2.0 * 3.14159265358979323846 * 25.0 * 0.003;
  EXPECT_NEAR(reference_path(r, Eigen::Vector3d::Zero(), 0.04).length_m,
              0.04 * std::sqrt(1.0 + c * c), 1e-17);
}

TEST(RestLength, StraightStringFoldingOnThePrecurvedBodyIsRefused) {
  // 400 1/m at a 3 mm offset: e3 . q* = 1 - 400 x 0.003 = -0.2 (was accepted and "converged").
  json doc = scenario(400.0, 0.040);
  doc["actuators"][0]["drive"] = {{"type", "tension"}, {"tension_N", 0.01}};
  expect_refused(doc, "actuators[0].routing.offset_m", "fold on the precurved body");
  // The same curvature with the string on the outer side is a regular path.
  doc["actuators"][0]["routing"]["offset_m"] = {-0.002, 0.0};
  EXPECT_NEAR(parse_scenario(doc).actuators[0].rest_length_m, 0.040 * (1.0 + 400.0 * 0.002),
              kRoundOff);
}

TEST(RestLength, HelixFoldingWhereItPassesTheCentreOfCurvatureIsRefused) {
  json doc = scenario(400.0, 0.040);
  doc["actuators"][0]["routing"] = {{"type", "helix"}, {"radius_m", 0.003}, {"turns_per_m", 25}};
  doc["actuators"][0]["drive"] = {{"type", "tension"}, {"tension_N", 0.01}};
  expect_refused(doc, "actuators[0].routing.radius_m", "fold on the precurved body");
}

TEST(RestLength, TendonOnAPrecurvedBodyHasZeroElongationAtRest) {
  // precurved-rod.json: its tendon's rest length is the reference path length (it was the
  // body length, which reported +0.88 mm of elongation with no load).
  const auto file =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" / "precurved-rod.json";
  const RodModel m = read_scenario(file.string());
  const Actuator& a = m.actuators.at(0);
  const Eigen::Vector3d q =
      Eigen::Vector3d::UnitZ() + m.reference_curvature_at(0.0).cross(a.routing.r(0.0));
  EXPECT_NEAR(a.rest_length_m / (m.length_m * q.norm()), 1.0, kRoundOff);
  EXPECT_GT(a.rest_length_m - m.length_m, 8e-4);  // the 0.88 mm that used to be reported
}

TEST(RestLength, TcaCoiledLengthMustMatchTheReferencePath) {
  // Reference path 40 mm x (1 + 5 1/m x 3 mm) = 40.6 mm (circular-manipulator.json).
  const double path = 0.040 * 1.015;
  EXPECT_NEAR(parse_scenario(scenario(-5.0, path * (1.0 + 0.9e-6))).actuators[0].rest_length_m,
              path, kRoundOff);
  expect_refused(scenario(-5.0, 0.040), "tcas.t.coiled_length_m",
                 "must equal the reference path length 0.0406 m");
  expect_refused(scenario(-5.0, path * (1.0 + 1.1e-6)), "tcas.t.coiled_length_m",
                 "within 1e-06 relative");
}

TEST(RestLength, PreElongationSetsTheRestLengthBelowThePath) {
  json doc = scenario(-5.0, 0.040);
  doc["actuators"][0]["pre_elongation_m"] = 0.0006;
  const Actuator a = parse_scenario(doc).actuators[0];
  EXPECT_NEAR(a.rest_length_m, 0.040 * 1.015 - 0.0006, kRoundOff);
}

TEST(RestLength, PreElongationOutsideWhatTheTcaCanHaveIsRefused) {
  json doc = scenario(0.0, 0.040);
  doc["actuators"][0]["pre_elongation_m"] = -0.0001;  // shorter than closed
  expect_refused(doc, "actuators[0].pre_elongation_m", "must be >= 0 for an extension TCA");
  doc["actuators"][0]["pre_elongation_m"] = 0.2;  // fiber 0.040/sin(15 deg) = 0.1545 m
  expect_refused(doc, "actuators[0].pre_elongation_m",
                 "(-coiled_length_m, fiber_length_m - coiled_length_m)");
  doc["actuators"][0]["pre_elongation_m"] = "0.001";
  expect_refused(doc, "actuators[0].pre_elongation_m", "must be a number");
  doc["actuators"][0]["pre_elongation_m"] = 0.001;
  doc["actuators"][0]["drive"] = {{"type", "tension"}, {"tension_N", 0.01}};
  expect_refused(doc, "actuators[0].pre_elongation_m", "applies only to a TCA drive");
}

TEST(RestLength, ContractionTcaMayBeShorterThanThePath) {
  json doc = scenario(0.0, 0.040);
  doc["tcas"]["t"]["kind"] = "contraction";
  doc["actuators"][0]["pre_elongation_m"] = -0.001;
  EXPECT_NEAR(parse_scenario(doc).actuators[0].rest_length_m, 0.041, kRoundOff);
  doc["actuators"][0]["pre_elongation_m"] = -0.040;  // a flat coil
  expect_refused(doc, "actuators[0].pre_elongation_m", "(-coiled_length_m");
}

}  // namespace
}  // namespace tcasim::rod
