// Strings anchored inside the body (docs/scenario-format.md "String extent"): span_m read and
// checked, the rest length over the span, the anchors as knots.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

constexpr double kRoundOff = 1e-13;

json scenario() {
  return json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "span-test",
    "body": {"length_m": 0.1, "section": {"shape": "circle", "diameter_m": 0.01},
             "material": {"youngs_modulus_Pa": 1e6, "poisson_ratio": 0.5}},
    "actuators": [{"name": "s", "routing": {"type": "straight", "offset_m": [0.003, 0.0]},
                   "span_m": [0.02, 0.06],
                   "drive": {"type": "tension", "tension_N": 1.0}}]
  })");
}

void expect_refused(const json& doc, const std::string& key, const std::string& value,
                    const std::string& rule) {
  try {
    (void)parse_scenario(doc);
    ADD_FAILURE() << "accepted; expected " << key << " to be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.value().find(value), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find(rule), std::string::npos) << e.what();
  }
}

TEST(StringSpan, SpanIsReadAndItsAnchorsAreKnots) {
  const RodModel m = parse_scenario(scenario());
  ASSERT_TRUE(m.actuators[0].span_m.has_value());
  EXPECT_EQ(m.actuators[0].span_start_m(), 0.02);
  EXPECT_EQ(m.actuators[0].span_end_m(m.length_m), 0.06);
  EXPECT_TRUE(m.has_inner_anchors());
  EXPECT_EQ(m.anchor_points(), (std::vector<double>{0.02, 0.06}));
  EXPECT_EQ(m.interior_knots(), (std::vector<double>{0.02, 0.06}));
  EXPECT_TRUE(m.breakpoints().empty());  // the body itself does not vary
  EXPECT_TRUE(m.uniform_body());
}

TEST(StringSpan, RestLengthIntegratesThePathOverTheSpanOnly) {
  json doc = scenario();
  EXPECT_NEAR(parse_scenario(doc).actuators[0].rest_length_m, 0.04, kRoundOff);
  // Precurved: the straight string's |q*| = 1 - omega*_y x is constant: 0.04 (1 - 20 0.003).
  doc["body"]["reference_curvature_1_m"] = {0.0, 20.0, 0.0};
  EXPECT_NEAR(parse_scenario(doc).actuators[0].rest_length_m, 0.04 * (1.0 - 20.0 * 0.003),
              kRoundOff);
  // A helix over [0.02, 0.06]: sqrt(1 + (2 pi k R)^2) times the span (phase does not matter).
  doc["body"].erase("reference_curvature_1_m");
  doc["actuators"][0]["routing"] = {
      {"type", "helix"}, {"radius_m", 0.003}, {"turns_per_m", 25.0}, {"phase_deg", 10.0}};
  const double c = 2.0 * 3.14159265358979323846 * 25.0 * 0.003;
  EXPECT_NEAR(parse_scenario(doc).actuators[0].rest_length_m, 0.04 * std::sqrt(1.0 + c * c),
              kRoundOff);
}

TEST(StringSpan, HelixSpanOnAPrecurvedBodyEqualsTheDifferenceOfTwoPrefixes) {
  Routing r;
  r.type = Routing::Type::kHelix;
  r.radius_m = 0.003;
  r.phase_rad = 0.3;
  r.turns_per_m = -137.0;
  const Eigen::Vector3d w(60.0, 80.0, 3.0);
  const double a = reference_path(r, w, 0.0, 0.013).length_m;
  const double b = reference_path(r, w, 0.0, 0.041).length_m;
  EXPECT_NEAR(reference_path(r, w, 0.013, 0.041).length_m / (b - a), 1.0, 1e-12);
}

TEST(StringSpan, DecreasingOrOutsideSpansAreRefusedNamingKeyValueAndRule) {
  json doc = scenario();
  doc["actuators"][0]["span_m"] = {0.06, 0.02};
  expect_refused(doc, "actuators[0].span_m", "0.06", "must be increasing");
  doc["actuators"][0]["span_m"] = {0.03, 0.03};
  expect_refused(doc, "actuators[0].span_m", "0.03", "must be increasing");
  doc["actuators"][0]["span_m"] = {-0.01, 0.05};
  expect_refused(doc, "actuators[0].span_m", "-0.01", "must lie inside the body [0, 0.1] m");
  doc["actuators"][0]["span_m"] = {0.0, 0.12};
  expect_refused(doc, "actuators[0].span_m", "0.12", "must lie inside the body");
  doc["actuators"][0]["span_m"] = {0.0};
  expect_refused(doc, "actuators[0].span_m", "[0.0]", "must be an array of 2 numbers");
  doc["actuators"][0]["span_m"] = {0.0, "x"};
  expect_refused(doc, "actuators[0].span_m[1]", "x", "must be a number");
}

}  // namespace
}  // namespace tcasim::rod
