// Profiles along the body (docs/scenario-format.md "Profiles along the body"): the Profile
// type, the model's properties along s, and the reader's rules for every profiled key.
#include "rod/profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"
#include "support/input_error.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

TEST(Profile, PiecewiseLinearWithOneSidedLimitsAtAJump) {
  const Profile p({0.0, 1.0, 1.0, 3.0}, {2.0, 4.0, 10.0, 6.0});
  EXPECT_DOUBLE_EQ(p.value(0.0), 2.0);
  EXPECT_DOUBLE_EQ(p.value(0.25), 2.5);
  EXPECT_DOUBLE_EQ(p.value(1.0, Side::kLeft), 4.0);
  EXPECT_DOUBLE_EQ(p.value(1.0, Side::kRight), 10.0);
  EXPECT_DOUBLE_EQ(p.value(2.0), 8.0);
  EXPECT_DOUBLE_EQ(p.value(2.0, Side::kLeft), 8.0);
  EXPECT_DOUBLE_EQ(p.value(3.0, Side::kLeft), 6.0);
  EXPECT_DOUBLE_EQ(p.value(3.0), 6.0);
  EXPECT_DOUBLE_EQ(p.value(0.0, Side::kLeft), 2.0);
  EXPECT_TRUE(p.jumps_at(1.0));
  EXPECT_FALSE(p.jumps_at(2.0));
  EXPECT_EQ(p.breakpoints(), (std::vector<double>{0.0, 1.0, 3.0}));
  EXPECT_DOUBLE_EQ(p.min_value(), 2.0);
  EXPECT_DOUBLE_EQ(p.max_value(), 10.0);
  const Profile c(5.0);
  EXPECT_TRUE(c.is_constant());
  EXPECT_DOUBLE_EQ(c.value(7.0, Side::kLeft), 5.0);
  EXPECT_THROW(Profile({0.0, 1.0, 1.0, 1.0}, {1, 2, 3, 4}), DomainError);
  EXPECT_THROW(Profile({0.0, 2.0, 1.0}, {1, 2, 3}), DomainError);
}

json body_doc() {
  return json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "profiles",
    "body": {"length_m": 0.2,
             "section": {"shape": "circle", "diameter_m": 0.01},
             "material": {"youngs_modulus_Pa": 1e6, "poisson_ratio": 0.5}}
  })");
}

TEST(ProfileScenario, TaperedCircleGivesPointwiseStiffnessAndMass) {
  json d = body_doc();
  d["body"]["section"]["diameter_m"] = {{"s_m", {0.0, 0.2}}, {"values", {0.01, 0.005}}};
  d["body"]["material"]["density_kg_m3"] = {{"s_m", {0.0, 0.1, 0.1, 0.2}},
                                            {"values", {1000, 1000, 2000, 2000}}};
  d["body"]["material"]["viscosity_Pa_s"] = 3.0;
  const RodModel m = parse_scenario(d);
  EXPECT_FALSE(m.uniform_body());
  EXPECT_EQ(m.breakpoints(), std::vector<double>{0.1});
  EXPECT_TRUE(m.jumps_at(0.1));
  EXPECT_TRUE(m.material.viscosity_profile.is_constant());
  EXPECT_DOUBLE_EQ(m.material.properties_at(0.1).viscosity_Pa_s, 3.0);
  const double d_mid = 0.0075;
  const double I = units::kPi * std::pow(d_mid, 4) / 64.0;
  EXPECT_NEAR(m.bending_torsion_stiffness(0.1).x(), 1e6 * I, 1e-12 * 1e6 * I);
  EXPECT_NEAR(m.bending_torsion_stiffness(0.1).z(), 1e6 / 3.0 * 2.0 * I, 1e-12 * 1e6 * I);
  const double A = units::kPi * d_mid * d_mid / 4.0;
  EXPECT_NEAR(m.mass_per_length_kg_m(0.1, Side::kLeft), 1000 * A, 1e-12);
  EXPECT_NEAR(m.mass_per_length_kg_m(0.1, Side::kRight), 2000 * A, 1e-12);
  // The properties at the base.
  EXPECT_DOUBLE_EQ(m.section.properties_at(0.0).width_m, 0.01);
  EXPECT_DOUBLE_EQ(m.section.properties_at(0.0).I_x_m4, units::kPi * std::pow(0.01, 4) / 64.0);
}

TEST(ProfileScenario, ConstantsGiveAUniformBodyWithTheSameNumbers) {
  const RodModel m = parse_scenario(body_doc());
  EXPECT_TRUE(m.uniform_body());
  EXPECT_TRUE(m.breakpoints().empty());
  EXPECT_EQ(m.shear_extension_stiffness(0.1), m.shear_extension_stiffness());
  EXPECT_DOUBLE_EQ(m.material.properties_at(0.1).viscosity_Pa_s, 0.0);
}

TEST(ProfileScenario, CurvatureComponentsAndRectangleAndCustomTakeProfiles) {
  json d = body_doc();
  d["body"]["section"] = {{"shape", "rectangle"},
                          {"width_m", 0.01},
                          {"height_m", {{"s_m", {0.0, 0.2}}, {"values", {0.01, 0.004}}}},
                          {"torsion", "saint-venant"}};
  d["body"]["reference_curvature_1_m"] = {
      1.0, json{{"s_m", {0.0, 0.05, 0.05, 0.2}}, {"values", {0.0, 0.0, 3.0, 3.0}}}, 0.0};
  const RodModel m = parse_scenario(d);
  EXPECT_EQ(m.reference_curvature_at(0.05, Side::kLeft), Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(m.reference_curvature_at(0.05, Side::kRight), Eigen::Vector3d(1.0, 3.0, 0.0));
  EXPECT_EQ(m.breakpoints(), std::vector<double>{0.05});
  const SectionProperties p = m.section.properties_at(0.2);
  EXPECT_DOUBLE_EQ(p.J_m4, rectangle_saint_venant_torsion(0.01, 0.004));
  d = body_doc();
  d["body"]["section"] = {{"shape", "custom"},
                          {"area_m2", 1e-4},
                          {"I_x_m4", {{"s_m", {0.0, 0.2}}, {"values", {1e-9, 2e-9}}}},
                          {"I_y_m4", 1e-9},
                          {"J_m4", 2e-9}};
  EXPECT_NEAR(parse_scenario(d).bending_torsion_stiffness(0.1).x(), 1.5e-3, 1e-15);
}

TEST(ProfileScenario, ReferencePathIntegratesAVaryingCurvature) {
  // A straight string at x = r on a body with omega*_y = k(s) (linear): |q*| = 1 - k r,
  // length = int (1 - k(s) r) ds = L - r (k0 + k1) L / 2.
  json d = body_doc();
  d["body"]["reference_curvature_1_m"] = {0.0, json{{"s_m", {0.0, 0.2}}, {"values", {1.0, 3.0}}},
                                          0.0};
  const RodModel m = parse_scenario(d);
  Routing r;
  r.offset_m = {0.003, 0.0};
  const ReferencePath ref = reference_path(r, m);
  EXPECT_NEAR(ref.length_m, 0.2 - 0.003 * 2.0 * 0.2, 1e-15);
  EXPECT_NEAR(ref.min_axial, 1.0 - 3.0 * 0.003, 1e-15);
  EXPECT_DOUBLE_EQ(ref.min_axial_s_m, 0.2);
}

void expect_rejected(const json& doc, const std::string& key, const std::string& rule) {
  test_support::expect_input_error([&] { (void)parse_scenario(doc); }, key, rule);
}

TEST(ProfileScenario, BadProfilesAreRejectedNamingKeyAndRule) {
  const std::string dk = "body.section.diameter_m";
  const auto with_d = [](const json& prof) {
    json d = body_doc();
    d["body"]["section"]["diameter_m"] = prof;
    return d;
  };
  expect_rejected(with_d({{"s_m", {0.0, 0.1, 0.05, 0.2}}, {"values", {1e-2, 1e-2, 1e-2, 1e-2}}}),
                  dk + ".s_m[2]", "never decreases");
  expect_rejected(with_d({{"s_m", {0.01, 0.2}}, {"values", {1e-2, 1e-2}}}), dk + ".s_m[0]",
                  "must be 0");
  expect_rejected(with_d({{"s_m", {0.0, 0.19}}, {"values", {1e-2, 1e-2}}}), dk + ".s_m[1]",
                  "must equal body.length_m");
  expect_rejected(with_d({{"s_m", {0.0, 0.2}}, {"values", {1e-2, 0.0}}}), dk + ".values[1]",
                  "must be positive");
  expect_rejected(with_d({{"s_m", {0.0, 0.1, 0.2}}, {"values", {1e-2, 1e-2}}}), dk + ".values",
                  "as many entries as s_m");
  expect_rejected(with_d({{"s_m", {0.0, 0.1, 0.1, 0.1, 0.2}}, {"values", {1, 1, 1, 1, 1}}}),
                  dk + ".s_m[3]", "third time");
  expect_rejected(with_d({{"s_m", {0.0}}, {"values", {1e-2}}}), dk + ".s_m", "at least two");
  expect_rejected(with_d({{"s_m", {0.0, 0.2}}, {"values", {1e-2, 1e-2}}, {"slope", 1}}),
                  dk + ".slope", "not an allowed key");
  expect_rejected(with_d("thin"), dk, "a number or a profile");
  json d = body_doc();
  d["body"]["material"]["viscosity_Pa_s"] = -1.0;
  expect_rejected(d, "body.material.viscosity_Pa_s", "must not be negative");
  d = body_doc();
  d["body"]["material"]["density_kg_m3"] = {{"s_m", {0.0, 0.2}}, {"values", {-1.0, 1.0}}};
  expect_rejected(d, "body.material.density_kg_m3.values[0]", "must not be negative");
  d = body_doc();
  d["body"]["reference_curvature_1_m"] = {0.0, json{{"s_m", {0.0, 0.3}}, {"values", {1, 1}}}, 0.0};
  expect_rejected(d, "body.reference_curvature_1_m[1].s_m[1]", "must equal body.length_m");
  // A straight string must fit where the tapered section is narrowest (the tip here).
  d = body_doc();
  d["body"]["section"]["diameter_m"] = {{"s_m", {0.0, 0.2}}, {"values", {0.01, 0.004}}};
  d["actuators"] = json::parse(R"([{"name": "t", "routing": {"type": "straight",
      "offset_m": [0.003, 0.0]}, "drive": {"type": "tension", "tension_N": 1}}])");
  expect_rejected(d, "actuators[0].routing.offset_m", "lies outside the body section");
  d["actuators"][0]["routing"]["offset_m"] = {0.002, 0.0};
  EXPECT_NO_THROW((void)parse_scenario(d));
  // A spline is held against the section at its own s: converging with the taper (4 mm at
  // the 10 mm base to 1.5 mm at the 4 mm tip) it fits, though not the narrowest section.
  d["actuators"][0]["routing"] = json::parse(R"({"type": "spline", "s_m": [0.0, 0.2],
      "offset_m": [[0.004, 0.0], [0.0015, 0.0]]})");
  EXPECT_NO_THROW((void)parse_scenario(d));
  d["actuators"][0]["routing"]["offset_m"] = {{0.0051, 0.0}, {0.0015, 0.0}};  // base radius 5 mm
  expect_rejected(d, "actuators[0].routing.offset_m[0]", "outside the body section at s = 0 m");
  // Diverging from the axis toward the narrow tip (radius 2 mm there).
  d["actuators"][0]["routing"]["offset_m"] = {{0.0, 0.0}, {0.0019, 0.0}};
  EXPECT_NO_THROW((void)parse_scenario(d));
  d["actuators"][0]["routing"]["offset_m"] = {{0.0, 0.0}, {0.0021, 0.0}};
  expect_rejected(d, "actuators[0].routing.offset_m[1]", "outside the body section at s = 0.2 m");
  // A linear spline past a neck of the section (a breakpoint between its two points).
  d["body"]["section"]["diameter_m"] = {{"s_m", {0.0, 0.1, 0.2}}, {"values", {0.01, 0.004, 0.01}}};
  d["actuators"][0]["routing"] = json::parse(R"({"type": "spline", "interpolation": "linear",
      "s_m": [0.0, 0.2], "offset_m": [[0.003, 0.0], [0.003, 0.0]]})");
  expect_rejected(d, "actuators[0].routing.offset_m", "outside the body section at s = 0.1 m");
  d = body_doc();
  d["body"]["reference_curvature_1_m"] = {0.0, 0.0};
  expect_rejected(d, "body.reference_curvature_1_m", "3 components");
}

}  // namespace
}  // namespace tcasim::rod
