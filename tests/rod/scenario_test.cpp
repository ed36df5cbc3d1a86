// Scenario reading: a full valid scenario gives the right numbers; every rule of
// docs/scenario-format.md rejects a bad value with its key path, value and rule.
#include "rod/scenario.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Closed-form section values evaluated in double precision.
constexpr double kRoundOff = 1e-13;

/// Every key of the format (and of our additions) with valid values.
const char* const kFullScenario = R"({
  "schema": "tcasim.scenario/1",
  "name": "rod-test-full",
  "comment": "every key of the format",
  "body": {
    "length_m": 0.040,
    "section": {"shape": "circle", "diameter_m": 0.008},
    "material": {"youngs_modulus_Pa": 37.8e3, "poisson_ratio": 0.5, "density_kg_m3": 1040},
    "reference_curvature_1_m": [0.5, -0.25, 0]
  },
  "gravity_m_s2": [0, 0, -9.81],
  "tip_load": {"force_N": [0.001, 0, 0], "moment_Nm": [0, 0.0002, 0]},
  "tip_constraint": {"position_m": [0.01, 0, 0.03], "normal": [0, 0, 2]},
  "base": {"position_m": [0.1, 0.2, 0.3], "rotation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]]},
  "tcas": {
    "manipulator-tca": {
      "kind": "extension", "coiled_length_m": 0.040, "pitch_angle_deg": 15,
      "outer_diameter_m": 0.0017, "twist_turns": 76.4,
      "material": {"source": "inline test values", "reference_temperature_degC": 25,
                   "youngs_modulus_Pa": {"polynomial_degC": [1.2e9, -2.0e6]},
                   "shear_modulus_Pa": 2.2e8, "diameter": {"linear_expansion_1_K": 1.0e-4},
                   "valid_range_degC": [20, 200], "f12_form": "paper"}
    },
    "gripper-tca": {
      "kind": "contraction", "coiled_length_m": 0.110, "fiber_length_m": 0.497,
      "outer_diameter_m": 0.002, "twist_turns": 300, "f12_form": "castigliano",
      "comment": "the 3-thread TCA of Sec. V-A",
      "material": {"source": "inline test values", "reference_temperature_degC": 25,
                   "youngs_modulus_Pa": 1.2e9, "shear_modulus_Pa": 2.2e8,
                   "diameter": {"linear_expansion_1_K": 1.0e-4}, "f12_form": "paper",
                   "valid_range_degC": [0, 150]}
    }
  },
  "actuators": [
    {"name": "tca", "routing": {"type": "straight", "offset_m": [0.003, 0.0]}, "count": 1,
     "pre_elongation_m": 3e-5,
     "drive": {"type": "tca", "tca": "manipulator-tca", "temperature_degC": 90}},
    {"name": "u-shaped", "comment": "two strings", "routing": {"type": "straight", "offset_m": [0, -0.002]},
     "count": 2, "pre_elongation_m": 0.002,
     "drive": {"type": "tca", "tca": "gripper-tca",
               "segments": [{"fraction": 0.25, "temperature_degC": 60},
                            {"fraction": 0.75, "temperature_degC": 120}]}},
    {"name": "tendon", "routing": {"type": "helix", "radius_m": 0.003, "phase_deg": 90, "turns_per_m": 25},
     "drive": {"type": "tension", "tension_N": 0.5}}
  ]
})";

json full() { return json::parse(kFullScenario); }

/// A minimal valid scenario: no TCAs, one tendon.
json minimal() {
  return json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "rod-test-minimal",
    "body": {"length_m": 0.05,
             "section": {"shape": "rectangle", "width_m": 0.010, "height_m": 0.004},
             "material": {"youngs_modulus_Pa": 1e5, "poisson_ratio": 0.3}},
    "actuators": [{"name": "t", "routing": {"type": "straight", "offset_m": [0.004, 0.001]},
                   "drive": {"type": "tension", "tension_N": 1.0}}]
  })");
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Parses `doc`, expecting an InputError whose key is `key`, whose value contains `value`
/// and whose rule contains `rule`; the message must show all three.
void expect_rejected(const json& doc, const std::string& key, const std::string& value,
                     const std::string& rule) {
  try {
    (void)parse_scenario(doc);
    ADD_FAILURE() << "accepted; expected rejection of " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_TRUE(contains(e.value(), value))
        << "value '" << e.value() << "' lacks '" << value << "'";
    EXPECT_TRUE(contains(e.rule(), rule)) << "rule '" << e.rule() << "' lacks '" << rule << "'";
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, key) && contains(what, value) && contains(what, rule)) << what;
  }
}

// ---------------------------------------------------------------------------------------
// Valid input

TEST(ParseScenario, FullScenarioGivesTheBodyNumbers) {
  const RodModel m = parse_scenario(full());
  EXPECT_EQ(m.schema, "tcasim.scenario/1");
  EXPECT_EQ(m.name, "rod-test-full");
  EXPECT_EQ(m.comment, "every key of the format");
  EXPECT_EQ(m.length_m, 0.040);
  const double d = 0.008;
  EXPECT_EQ(m.section.shape, Section::Shape::kCircle);
  const SectionProperties p = m.section.properties_at(0.0);
  EXPECT_NEAR(p.area_m2, units::kPi * d * d / 4.0, kRoundOff * 1e-4);
  EXPECT_NEAR(p.I_x_m4 / (units::kPi * std::pow(d, 4) / 64.0), 1.0, kRoundOff);
  EXPECT_NEAR(p.I_y_m4 / p.I_x_m4, 1.0, kRoundOff);
  // Polar moment (the default), which for a circle is also the Saint-Venant constant.
  EXPECT_NEAR(p.J_m4 / (units::kPi * std::pow(d, 4) / 32.0), 1.0, kRoundOff);
  const MaterialProperties mat = m.material.properties_at(0.0);
  EXPECT_EQ(mat.youngs_modulus_Pa, 37.8e3);
  // G = E/(2 (1 + nu)) with nu = 0.5 (EcoFlex, as in the paper).
  EXPECT_NEAR(mat.shear_modulus_Pa, 12.6e3, 1e-9);
  EXPECT_EQ(mat.density_kg_m3, 1040.0);
  EXPECT_EQ(m.reference_curvature_at(0.0), Eigen::Vector3d(0.5, -0.25, 0.0));
  EXPECT_EQ(m.gravity_W_m_s2, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_EQ(m.tip_force_W_N, Eigen::Vector3d(0.001, 0, 0));
  EXPECT_EQ(m.tip_moment_W_Nm, Eigen::Vector3d(0, 0.0002, 0));
  ASSERT_TRUE(m.tip_constraint.has_value());
  EXPECT_EQ(m.tip_constraint->position_W_m, Eigen::Vector3d(0.01, 0, 0.03));
  ASSERT_TRUE(m.tip_constraint->normal_W.has_value());
  EXPECT_NEAR((*m.tip_constraint->normal_W - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, kRoundOff);
  EXPECT_EQ(m.base_position_W_m, Eigen::Vector3d(0.1, 0.2, 0.3));
  Eigen::Matrix3d R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // row-major in the file
  EXPECT_NEAR((m.R_WB0 - R).norm(), 0.0, kRoundOff);
}

TEST(ParseScenario, FullScenarioGivesTheTcasAndActuators) {
  const RodModel m = parse_scenario(full());
  ASSERT_EQ(m.tcas.size(), 2u);
  const tca::Tca& manip = *m.tcas.at("manipulator-tca");
  EXPECT_EQ(manip.parameters().kind, tca::Kind::kExtension);
  EXPECT_NEAR(manip.parameters().fiber_length_m, 0.040 / std::sin(units::deg_to_rad(15.0)), 1e-15);
  // No f12_form on the TCA: the material's ("paper") applies.
  EXPECT_EQ(manip.parameters().f12_form, tca::F12Form::kPaper);
  EXPECT_NEAR(manip.material().max_temperature_K, units::degC_to_K(200.0), 1e-12);
  const tca::Tca& grip = *m.tcas.at("gripper-tca");
  EXPECT_EQ(grip.parameters().kind, tca::Kind::kContraction);
  EXPECT_EQ(grip.parameters().fiber_length_m, 0.497);
  // The TCA's own f12_form overrides its material's.
  EXPECT_EQ(grip.parameters().f12_form, tca::F12Form::kCastigliano);

  ASSERT_EQ(m.actuators.size(), 3u);
  const Actuator& a0 = m.actuators[0];
  EXPECT_EQ(a0.name, "tca");
  EXPECT_EQ(a0.routing.type, Routing::Type::kStraight);
  EXPECT_EQ(a0.routing.offset_m, Eigen::Vector2d(0.003, 0.0));
  EXPECT_EQ(a0.drive.type, Drive::Type::kTca);
  EXPECT_EQ(a0.drive.tca.get(), &manip);
  EXPECT_FALSE(a0.drive.segmented);
  ASSERT_EQ(a0.drive.segments.size(), 1u);
  EXPECT_EQ(a0.drive.segments[0].fraction, 1.0);
  EXPECT_NEAR(a0.drive.segments[0].temperature_K, 363.15, 1e-12);
  // Reference path L (1 - omega*_y r_x) = 0.040 x 1.00075 less the pre-elongation 3e-5.
  EXPECT_NEAR(a0.rest_length_m, 0.040 * 1.00075 - 3e-5, kRoundOff);

  const Actuator& a1 = m.actuators[1];
  EXPECT_EQ(a1.count, 2);
  EXPECT_TRUE(a1.drive.segmented);
  ASSERT_EQ(a1.drive.segments.size(), 2u);
  EXPECT_EQ(a1.drive.segments[1].fraction, 0.75);
  EXPECT_NEAR(a1.drive.segments[1].temperature_K, 393.15, 1e-12);
  // Reference path L (1 + omega*_x r_y) = 0.040 x 0.999 less the pre-elongation 0.002.
  EXPECT_NEAR(a1.rest_length_m, 0.040 * 0.999 - 0.002, kRoundOff);

  const Actuator& a2 = m.actuators[2];
  EXPECT_EQ(a2.routing.type, Routing::Type::kHelix);
  EXPECT_EQ(a2.routing.radius_m, 0.003);
  EXPECT_NEAR(a2.routing.phase_rad, units::kPi / 2.0, kRoundOff);
  EXPECT_EQ(a2.routing.turns_per_m, 25.0);
  EXPECT_EQ(a2.drive.type, Drive::Type::kTension);
  EXPECT_EQ(a2.drive.tension_N, 0.5);
  EXPECT_EQ(a2.count, 1);  // default
}

TEST(ParseScenario, TendonRestLengthIsThePathLengthByQuadrature) {
  const RodModel m = parse_scenario(full());
  const Actuator& helix = m.actuators[2];
  // Composite Simpson of |e3 + omega* x r + r'| over [0, L] with the routing's own r and
  // derivative: an independent check of the reader's period-wise Gauss-Legendre quadrature
  // (the integrand is smooth and periodic; the body is precurved).
  constexpr int kIntervals = 2000;
  const double h = m.length_m / kIntervals;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    const double s = i * h;
    const double f = (Eigen::Vector3d::UnitZ() +
                      m.reference_curvature_at(s).cross(helix.routing.r(s)) + helix.routing.dr(s))
                         .norm();
    sum += f * ((i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0));
  }
  const double quadrature = sum * h / 3.0;
  EXPECT_NEAR(helix.rest_length_m, quadrature, 1e-14);
  EXPECT_GT(helix.rest_length_m, m.length_m);

  const RodModel straight = parse_scenario(minimal());
  EXPECT_EQ(straight.actuators[0].rest_length_m, 0.05);
}

TEST(ParseScenario, RectangleSectionGivesSecondMomentsAboutBodyAxes) {
  const RodModel m = parse_scenario(minimal());
  const double w = 0.010, h = 0.004;
  EXPECT_EQ(m.section.shape, Section::Shape::kRectangle);
  const SectionProperties p = m.section.properties_at(0.0);
  EXPECT_NEAR(p.area_m2, w * h, 1e-18);
  EXPECT_NEAR(p.I_x_m4 / (w * h * h * h / 12.0), 1.0, kRoundOff);
  EXPECT_NEAR(p.I_y_m4 / (h * w * w * w / 12.0), 1.0, kRoundOff);
  EXPECT_GT(p.I_y_m4, p.I_x_m4);  // wider along x: stiffer about y
  EXPECT_NEAR(p.J_m4 / (p.I_x_m4 + p.I_y_m4), 1.0, kRoundOff);
  EXPECT_FALSE(m.section.saint_venant_torsion);
  EXPECT_NEAR(m.material.properties_at(0.0).shear_modulus_Pa, 1e5 / 2.6, 1e-9);
  EXPECT_EQ(m.material.properties_at(0.0).density_kg_m3, 0.0);  // massless by default
  EXPECT_EQ(m.R_WB0, Eigen::Matrix3d::Identity());
  EXPECT_FALSE(m.tip_constraint.has_value());
  EXPECT_TRUE(m.tcas.empty());
}

/// Saint-Venant torsion constant of an a x b rectangle (a >= b) is k1 a b^3.
double saint_venant(double w, double h) {
  json doc = minimal();
  doc["body"]["section"] = {
      {"shape", "rectangle"}, {"width_m", w}, {"height_m", h}, {"torsion", "saint-venant"}};
  doc["actuators"] = json::array();  // its offset would not fit every rectangle
  const RodModel m = parse_scenario(doc);
  EXPECT_TRUE(m.section.saint_venant_torsion);
  return m.section.properties_at(0.0).J_m4;
}

TEST(ParseScenario, SaintVenantTorsionMatchesTabulatedRectangleCoefficients) {
  // Square: k1 = 0.1405770 (series value to 7 digits; Timoshenko & Goodier tabulate 0.141).
  EXPECT_NEAR(saint_venant(0.01, 0.01) / 1e-8, 0.1405770, 1e-7);
  // Timoshenko & Goodier, Theory of Elasticity, Sec. 109 table (3 digits): a/b = 2: 0.229,
  // a/b = 10: 0.312. Tolerance: half a unit of the table's last digit.
  EXPECT_NEAR(saint_venant(0.02, 0.01) / (0.02 * 1e-6), 0.229, 5e-4);
  EXPECT_NEAR(saint_venant(0.001, 0.01) / (0.01 * 1e-9), 0.312, 5e-4);
  // Independent of which side is called the width.
  EXPECT_NEAR(saint_venant(0.004, 0.010) / saint_venant(0.010, 0.004), 1.0, kRoundOff);
  // Always below the polar moment (which overestimates torsion stiffness).
  EXPECT_LT(saint_venant(0.010, 0.004), 0.010 * 0.004 * (0.010 * 0.010 + 0.004 * 0.004) / 12.0);
}

TEST(ParseScenario, CircleSaintVenantEqualsPolarAndCustomIsTakenAsGiven) {
  json doc = full();
  doc["body"]["section"]["torsion"] = "saint-venant";
  const SectionProperties c = parse_scenario(doc).section.properties_at(0.0);
  EXPECT_NEAR(c.J_m4 / (c.I_x_m4 + c.I_y_m4), 1.0, kRoundOff);

  doc = minimal();
  doc["body"]["section"] = {{"shape", "custom"},
                            {"area_m2", 1e-5},
                            {"I_x_m4", 2e-11},
                            {"I_y_m4", 3e-11},
                            {"J_m4", 4e-11}};
  const RodModel m = parse_scenario(doc);
  EXPECT_EQ(m.section.shape, Section::Shape::kCustom);
  const SectionProperties p = m.section.properties_at(0.0);
  EXPECT_EQ(p.area_m2, 1e-5);
  EXPECT_EQ(p.I_x_m4, 2e-11);
  EXPECT_EQ(p.I_y_m4, 3e-11);
  EXPECT_EQ(p.J_m4, 4e-11);
}

TEST(ParseScenario, MaterialWithoutF12FormDefaultsToCastigliano) {
  json doc = full();
  doc["tcas"]["gripper-tca"].erase("f12_form");
  doc["tcas"]["gripper-tca"]["material"].erase("f12_form");
  EXPECT_EQ(parse_scenario(doc).tcas.at("gripper-tca")->parameters().f12_form,
            tca::F12Form::kCastigliano);
}

TEST(ParseScenario, OffsetOnTheEdgeOrInTheRectangleCornerIsInside) {
  json doc = minimal();
  doc["actuators"][0]["routing"]["offset_m"] = {0.005, 0.002};  // the corner
  EXPECT_NO_THROW(parse_scenario(doc));
  doc["actuators"][0]["routing"]["offset_m"] = {-0.005, 0.0};  // the edge
  EXPECT_NO_THROW(parse_scenario(doc));
  doc["actuators"] = json::array();  // no actuators: a passive rod
  EXPECT_TRUE(parse_scenario(doc).actuators.empty());
}

TEST(ParseScenario, ShippedMaterialIsLoadedFromTheDataDirectory) {
  ASSERT_EQ(setenv("TCASIM_DATA_DIR", TCASIM_ROD_TEST_DATA_DIR, 1), 0);
  EXPECT_EQ(data_directory(), TCASIM_ROD_TEST_DATA_DIR);
  json doc = full();
  doc["tcas"]["gripper-tca"]["material"] = "test-nylon";
  doc["tcas"]["gripper-tca"].erase("f12_form");
  const RodModel m = parse_scenario(doc);
  const tca::Material& mat = m.tcas.at("gripper-tca")->material();
  EXPECT_EQ(mat.name, "test-nylon");
  EXPECT_EQ(mat.diameter.type, tca::DiameterLaw::Type::kRatioPolynomial);
  EXPECT_EQ(mat.youngs_modulus_Pa.coefficients, (std::vector<double>{1.2e9, -2.0e6}));
  EXPECT_NEAR(mat.min_temperature_K, units::degC_to_K(20.0), 1e-12);
  EXPECT_EQ(m.tcas.at("gripper-tca")->parameters().f12_form, tca::F12Form::kPaper);

  // Unknown name: the message lists what is available.
  doc["tcas"]["gripper-tca"]["material"] = "no-such-material";
  expect_rejected(doc, "tcas.gripper-tca.material", "no-such-material", "test-nylon");
  // A path is not a name.
  doc["tcas"]["gripper-tca"]["material"] = "../materials/test-nylon";
  expect_rejected(doc, "tcas.gripper-tca.material", "../materials", "not a path");
  // An error inside the file names the file and the key in it.
  doc["tcas"]["gripper-tca"]["material"] = "test-broken";
  try {
    (void)parse_scenario(doc);
    ADD_FAILURE() << "accepted a negative modulus";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.key(), "test-broken.json:youngs_modulus_Pa")) << e.what();
    EXPECT_TRUE(contains(e.rule(), "must be positive")) << e.what();
  }
  ASSERT_EQ(unsetenv("TCASIM_DATA_DIR"), 0);
}

// ---------------------------------------------------------------------------------------
// Files

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("tcasim_rod_test_" + name);
  std::ofstream(path) << text;
  return path.string();
}

TEST(ReadScenario, ReadsAFileAndNamesTheFileOnIoAndJsonErrors) {
  const std::string good = write_temp("good.json", kFullScenario);
  EXPECT_EQ(read_scenario(good).name, "rod-test-full");

  const std::string missing = "/nonexistent-dir/scenario.json";
  try {
    (void)read_scenario(missing);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), missing) && contains(e.what(), "cannot be opened")) << e.what();
  }
  const std::string bad = write_temp("bad.json", "{\"schema\": ");
  try {
    (void)read_scenario(bad);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), bad) && contains(e.what(), "not valid JSON")) << e.what();
  }
  std::filesystem::remove(good);
  std::filesystem::remove(bad);
}

TEST(ReadTcas, ReadsATcaFileOrTheTcasOfAScenario) {
  json tcas_file = {{"schema", "tcasim.tcas/1"},
                    {"name", "test-tcas"},
                    {"comment", "two TCAs"},
                    {"tcas", full()["tcas"]}};
  const std::string a = write_temp("tcas.json", tcas_file.dump());
  const auto from_tca_file = read_tcas(a);
  ASSERT_EQ(from_tca_file.size(), 2u);
  EXPECT_EQ(from_tca_file.at("gripper-tca")->parameters().twist_turns, 300.0);

  const std::string b = write_temp("scenario-tcas.json", kFullScenario);
  EXPECT_EQ(read_tcas(b).size(), 2u);

  tcas_file["schema"] = "tcasim.result/1";
  const std::string c = write_temp("wrong-schema.json", tcas_file.dump());
  try {
    (void)read_tcas(c);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "schema");
    EXPECT_TRUE(contains(e.rule(), "tcasim.tcas/1")) << e.what();
  }
  tcas_file["schema"] = "tcasim.tcas/1";
  tcas_file["actuators"] = json::array();
  const std::string d = write_temp("extra-key.json", tcas_file.dump());
  EXPECT_THROW(read_tcas(d), InputError);
  for (const auto& p : {a, b, c, d}) std::filesystem::remove(p);
}

// ---------------------------------------------------------------------------------------
// One test per rejection rule

TEST(RejectScenario, WrongSchema) {
  json doc = full();
  doc["schema"] = "tcasim.scenario/2";
  expect_rejected(doc, "schema", "\"tcasim.scenario/2\"", "must be one of: tcasim.scenario/1");
}

TEST(RejectScenario, UnknownKeyListsTheAllowedOnes) {
  json doc = full();
  doc["gravity"] = {0, 0, -9.81};
  expect_rejected(doc, "gravity", "[0,0,-9.81]",
                  "allowed: schema, name, comment, body, gravity_m_s2");
  doc = full();
  doc["body"]["section"]["radius_m"] = 0.004;
  expect_rejected(doc, "body.section.radius_m", "0.004", "allowed: shape, torsion, diameter_m");
  doc = full();
  doc["actuators"][2]["drive"]["temperature_degC"] = 50;  // a tension drive has no temperature
  expect_rejected(doc, "actuators[2].drive.temperature_degC", "50", "is not an allowed key");
  doc = minimal();
  doc["body"]["section"] = {{"shape", "custom"}, {"area_m2", 1e-5}, {"I_x_m4", 2e-11},
                            {"I_y_m4", 3e-11},   {"J_m4", 4e-11},   {"torsion", "saint-venant"}};
  expect_rejected(doc, "body.section.torsion", "saint-venant", "is not an allowed key");
}

TEST(RejectScenario, WrongType) {
  json doc = full();
  doc["body"]["length_m"] = "0.04";
  expect_rejected(doc, "body.length_m", "\"0.04\"", "must be a number, not string");
  doc = full();
  doc["name"] = 7;
  expect_rejected(doc, "name", "7", "must be a string");
  doc = full();
  doc["gravity_m_s2"] = {0, -9.81};
  expect_rejected(doc, "gravity_m_s2", "[0,-9.81]", "must be an array of 3 numbers");
  doc = full();
  doc["tip_load"]["force_N"][1] = true;
  expect_rejected(doc, "tip_load.force_N[1]", "true", "must be a number");
}

TEST(RejectScenario, MissingRequiredKey) {
  json doc = full();
  doc["body"].erase("length_m");
  expect_rejected(doc, "body.length_m", "(missing)", "is required");
  doc = full();
  doc["actuators"][0].erase("drive");
  expect_rejected(doc, "actuators[0].drive", "(missing)", "is required");
  doc = full();
  doc["tcas"]["manipulator-tca"]["material"].erase("source");
  expect_rejected(doc, "tcas.manipulator-tca.material.source", "(missing)", "is required");
}

TEST(RejectScenario, NonPositiveLength) {
  json doc = full();
  doc["body"]["length_m"] = 0;
  expect_rejected(doc, "body.length_m", "0", "must be positive");
  doc = full();
  doc["body"]["section"]["diameter_m"] = -0.008;
  expect_rejected(doc, "body.section.diameter_m", "-0.008", "must be positive");
  doc = full();
  doc["tcas"]["manipulator-tca"]["outer_diameter_m"] = 0;
  expect_rejected(doc, "tcas.manipulator-tca.outer_diameter_m", "0", "must be positive");
}

TEST(RejectScenario, NonFiniteNumber) {
  json doc = full();
  doc["body"]["length_m"] = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(doc, "body.length_m", "nan", "must be a finite number");
  doc = full();
  doc["tip_load"]["moment_Nm"][2] = std::numeric_limits<double>::infinity();
  expect_rejected(doc, "tip_load.moment_Nm[2]", "inf", "must be a finite number");
}

TEST(RejectScenario, PoissonRatioOutsideZeroToOneHalf) {
  json doc = full();
  doc["body"]["material"]["poisson_ratio"] = 0.6;
  expect_rejected(doc, "body.material.poisson_ratio", "0.6", "must lie in [0, 0.5]");
  doc["body"]["material"]["poisson_ratio"] = -0.1;
  expect_rejected(doc, "body.material.poisson_ratio", "-0.1", "must lie in [0, 0.5]");
}

TEST(RejectScenario, GravityWithoutDensity) {
  json doc = full();
  doc["body"]["material"].erase("density_kg_m3");
  expect_rejected(doc, "body.material.density_kg_m3", "(missing)", "is required when gravity_m_s2");
}

TEST(RejectScenario, UnknownSectionShape) {
  json doc = full();
  doc["body"]["section"]["shape"] = "hexagon";
  expect_rejected(doc, "body.section.shape", "\"hexagon\"",
                  "must be one of: circle, rectangle, custom");
}

TEST(RejectScenario, CountNotAPositiveInteger) {
  json doc = full();
  doc["actuators"][1]["count"] = 0;
  expect_rejected(doc, "actuators[1].count", "0", "must be an integer in [1, 1000]");
  doc["actuators"][1]["count"] = -3;
  expect_rejected(doc, "actuators[1].count", "-3", "must be an integer in [1, 1000]");
  doc["actuators"][1]["count"] = 1.5;
  expect_rejected(doc, "actuators[1].count", "1.5", "must be an integer");
}

TEST(RejectScenario, CountAboveTheBound) {
  json doc = full();
  doc["actuators"][1]["count"] = 1001;
  expect_rejected(doc, "actuators[1].count", "1001", "must be an integer in [1, 1000]");
  doc["actuators"][1]["count"] = 1000000000;  // was accepted and "converged"
  expect_rejected(doc, "actuators[1].count", "1000000000", "must be an integer in [1, 1000]");
  doc["actuators"][1]["count"] = 1e9;  // a JSON float
  expect_rejected(doc, "actuators[1].count", "1000000000.0", "must be an integer in [1, 1000]");
  doc["actuators"][1]["count"] = 1000;
  EXPECT_EQ(parse_scenario(doc).actuators[1].count, 1000);
}

TEST(RejectScenario, TooManySegmentsOrActuators) {
  json doc = full();
  json segs = json::array();
  for (int i = 0; i < 1001; ++i)
    segs.push_back({{"fraction", 1.0 / 1001}, {"temperature_degC", 60}});
  doc["actuators"][1]["drive"]["segments"] = segs;
  expect_rejected(doc, "actuators[1].drive.segments", "1001 segments",
                  "must have at most 1000 segments");
  doc = full();
  json acts = json::array();
  for (int i = 0; i < 257; ++i) {
    json a = doc["actuators"][2];
    a["name"] = "t" + std::to_string(i);
    acts.push_back(a);
  }
  doc["actuators"] = acts;
  expect_rejected(doc, "actuators", "257 actuators", "must have at most 256 actuators");
}

TEST(RejectScenario, DuplicateActuatorName) {
  json doc = full();
  doc["actuators"][2]["name"] = "tca";
  expect_rejected(doc, "actuators[2].name", "\"tca\"", "is not unique (also actuators[0].name)");
}

TEST(RejectScenario, DriveNamesAnUndefinedTca) {
  json doc = full();
  doc["actuators"][0]["drive"]["tca"] = "missing-tca";
  expect_rejected(doc, "actuators[0].drive.tca", "\"missing-tca\"",
                  "is not a key of tcas (defined: gripper-tca, manipulator-tca)");
}

TEST(RejectScenario, DriveWithBothOrNeitherTemperatureAndSegments) {
  json doc = full();
  doc["actuators"][1]["drive"]["temperature_degC"] = 80;
  expect_rejected(doc, "actuators[1].drive.segments", "fraction", "give exactly one");
  doc = full();
  doc["actuators"][0]["drive"].erase("temperature_degC");
  expect_rejected(doc, "actuators[0].drive.temperature_degC", "(missing)", "unless segments");
}

TEST(RejectScenario, SegmentFractionOutsideZeroToOne) {
  json doc = full();
  doc["actuators"][1]["drive"]["segments"][0]["fraction"] = 0;
  expect_rejected(doc, "actuators[1].drive.segments[0].fraction", "0", "must lie in (0, 1]");
}

TEST(RejectScenario, SegmentFractionsNotSummingToOne) {
  json doc = full();
  doc["actuators"][1]["drive"]["segments"][1]["fraction"] = 0.65;
  expect_rejected(doc, "actuators[1].drive.segments", "0.9", "must have fractions summing to 1");
  // Within 1e-9 is accepted.
  doc["actuators"][1]["drive"]["segments"][1]["fraction"] = 0.75 + 5e-10;
  EXPECT_NO_THROW(parse_scenario(doc));
}

TEST(RejectScenario, TemperatureBelowAbsoluteZero) {
  json doc = full();
  doc["actuators"][0]["drive"]["temperature_degC"] = -400;
  try {
    (void)parse_scenario(doc);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "actuators[0].drive.temperature_degC = -400 is below absolute zero");
  }
  doc = full();
  doc["actuators"][1]["drive"]["segments"][1]["temperature_degC"] = -273.15;
  expect_rejected(doc, "actuators[1].drive.segments[1].temperature_degC", "-273.15",
                  "is not above absolute zero");
}

TEST(RejectScenario, TemperatureOutsideTheMaterialRange) {
  json doc = full();
  doc["actuators"][0]["drive"]["temperature_degC"] = 250;
  expect_rejected(doc, "actuators[0].drive.temperature_degC", "250",
                  "is outside the valid range [20, 200] degC");
}

TEST(RejectScenario, StraightOffsetOutsideTheSection) {
  json doc = full();
  doc["actuators"][0]["routing"]["offset_m"] = {0.003, 0.003};  // |r| = 4.24 mm > 4 mm
  expect_rejected(doc, "actuators[0].routing.offset_m", "[0.003,0.003]",
                  "lies outside the body section");
  doc = minimal();
  doc["actuators"][0]["routing"]["offset_m"] = {0.004, 0.0021};  // above the 2 mm top edge
  expect_rejected(doc, "actuators[0].routing.offset_m", "[0.004,0.0021]",
                  "outside the body section");
}

TEST(RejectScenario, HelixRadiusNotPositiveOrOutsideTheSection) {
  json doc = full();
  doc["actuators"][2]["routing"]["radius_m"] = 0;
  expect_rejected(doc, "actuators[2].routing.radius_m", "0", "must be positive");
  doc["actuators"][2]["routing"]["radius_m"] = 0.0041;
  expect_rejected(doc, "actuators[2].routing.radius_m", "0.0041",
                  "puts the helix outside the body section");
  doc = minimal();
  doc["actuators"][0]["routing"] = {{"type", "helix"}, {"radius_m", 0.003}, {"turns_per_m", 10}};
  // Fits along x (5 mm) but not along y (2 mm).
  expect_rejected(doc, "actuators[0].routing.radius_m", "0.003", "narrowest half extent 0.002");
}

TEST(RejectScenario, BaseRotationNotOrthonormal) {
  json doc = full();
  doc["base"]["rotation"] = {{1, 0, 0}, {0, 1, 1e-6}, {0, 0, 1}};
  expect_rejected(doc, "base.rotation", "[[1,0,0]", "must be orthonormal");
  doc["base"]["rotation"] = {{1, 0, 0}, {0, 1}, {0, 0, 1}};
  expect_rejected(doc, "base.rotation", "[[1,0,0]", "must be a 3x3 array");
}

TEST(RejectScenario, BaseRotationIsAReflection) {
  json doc = full();
  doc["base"]["rotation"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  expect_rejected(doc, "base.rotation", "[[1,0,0],[0,1,0],[0,0,-1]]", "must have determinant +1");
}

TEST(RejectScenario, TipConstraintNormalIsZero) {
  json doc = full();
  doc["tip_constraint"]["normal"] = {0, 0, 0};
  expect_rejected(doc, "tip_constraint.normal", "[0,0,0]", "must be non-zero");
}

TEST(RejectScenario, TcaWithBothOrNeitherFiberLengthAndPitchAngle) {
  json doc = full();
  doc["tcas"]["manipulator-tca"]["fiber_length_m"] = 0.15;
  expect_rejected(doc, "tcas.manipulator-tca.pitch_angle_deg", "15", "give exactly one");
  doc = full();
  doc["tcas"]["manipulator-tca"].erase("pitch_angle_deg");
  expect_rejected(doc, "tcas.manipulator-tca.fiber_length_m", "(missing)",
                  "unless pitch_angle_deg");
  doc = full();
  doc["tcas"]["manipulator-tca"]["pitch_angle_deg"] = 90;
  expect_rejected(doc, "tcas.manipulator-tca.pitch_angle_deg", "90", "must lie in (0, 90)");
}

TEST(RejectScenario, TcaConstructorErrorCarriesTheFullKeyPath) {
  json doc = full();
  doc["tcas"]["gripper-tca"]["fiber_length_m"] = 0.1;  // l < L = 0.11
  expect_rejected(doc, "tcas.gripper-tca.coiled_length_m", "0.11", "fiber_length_m");
}

TEST(RejectScenario, TcaKindUnknown) {
  json doc = full();
  doc["tcas"]["gripper-tca"]["kind"] = "torsional";
  expect_rejected(doc, "tcas.gripper-tca.kind", "\"torsional\"",
                  "must be one of: extension, contraction");
}

TEST(RejectScenario, MaterialPropertyMalformedOrNotPositive) {
  json doc = full();
  auto& mat = doc["tcas"]["manipulator-tca"]["material"];
  mat["youngs_modulus_Pa"] = {{"polynomial_degC", json::array()}};
  expect_rejected(doc, "tcas.manipulator-tca.material.youngs_modulus_Pa.polynomial_degC", "[]",
                  "non-empty array");
  // E = 1.2e9 - 1e7 T becomes negative at 120 degC, inside the valid range [20, 200].
  mat["youngs_modulus_Pa"] = {{"polynomial_degC", {1.2e9, -1.0e7}}};
  expect_rejected(doc, "tcas.manipulator-tca.material.youngs_modulus_Pa", "", "must be positive");
  mat["youngs_modulus_Pa"] = 1e9;
  mat["diameter"] = {{"linear_expansion_1_K", 1e-4}, {"ratio_polynomial_degC", {1.0}}};
  expect_rejected(doc, "tcas.manipulator-tca.material.diameter", "linear_expansion_1_K",
                  "exactly one");
  mat["diameter"] = {{"linear_expansion_1_K", 1e-4}};
  mat["valid_range_degC"] = {200, 20};
  expect_rejected(doc, "tcas.manipulator-tca.material.valid_range_degC", "[200,20]", "lo < hi");
  mat["valid_range_degC"] = {30, 200};  // excludes the 25 degC reference
  expect_rejected(doc, "tcas.manipulator-tca.material.reference_temperature_degC", "25",
                  "must lie inside valid_range_degC");
}

TEST(RejectScenario, MaterialWithoutValidRange) {
  // An inline material without a range was taken as valid on [0 K, 1e9 K].
  json doc = full();
  doc["tcas"]["manipulator-tca"]["material"].erase("valid_range_degC");
  expect_rejected(doc, "tcas.manipulator-tca.material.valid_range_degC", "(missing)",
                  "is required");
  doc = full();
  doc["tcas"]["manipulator-tca"]["material"]["valid_range_degC"] = {-300, 200};
  expect_rejected(doc, "tcas.manipulator-tca.material.valid_range_degC[0]", "-300",
                  "below absolute zero");
}

}  // namespace
}  // namespace tcasim::rod

namespace tcasim::rod {
namespace {

// The project's own files must satisfy the reader (scenario files under
// validation/scenarios/, its dynamic suite validation/scenarios/dynamic/ and its contact suite
// validation/scenarios/contact/, materials under data/materials/).
TEST(ShippedFiles, ValidationScenariosAndMaterialsParse) {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  int parsed = 0;
  std::vector<std::filesystem::path> files;
  for (const auto& d : {dir, dir / "dynamic", dir / "contact"}) {
    for (const auto& entry : std::filesystem::directory_iterator(d)) files.push_back(entry.path());
  }
  for (const auto& file : files) {
    if (file.extension() != ".json") continue;
    const std::string path = file.string();
    try {
      const json doc = json::parse(std::ifstream(path));
      if (doc.contains("schema") && doc.at("schema") == "tcasim.tcas/1") {
        EXPECT_FALSE(read_tcas(path).empty()) << path;
      } else {
        const RodModel m = read_scenario(path);
        EXPECT_FALSE(m.name.empty()) << path;
        EXPECT_FALSE(m.comment.empty()) << path << " has no comment";
      }
      ++parsed;
    } catch (const std::exception& e) {
      ADD_FAILURE() << path << ": " << e.what();
    }
  }
  EXPECT_GT(parsed, 0);
  for (const auto& entry : std::filesystem::directory_iterator(data_directory() + "/materials")) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    EXPECT_NO_THROW({
      const tca::Material m = load_material(name, "test");
      EXPECT_EQ(m.name, name);
      EXPECT_FALSE(m.source.empty());
    }) << name;
  }
}

}  // namespace
}  // namespace tcasim::rod

namespace tcasim::rod {
namespace {

TEST(WithTcaMaterial, RebuildsEveryTcaOnTheMaterialAndRepointsTheActuators) {
  const std::filesystem::path file = std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" /
                                     "scenarios" / "square-manipulator.json";
  const RodModel base = read_scenario(file.string());
  const tca::Material other = load_material("silver-nylon-castigliano", "material");
  const RodModel m = with_tca_material(base, other, tca::F12Form::kPaper);
  ASSERT_EQ(m.tcas.size(), base.tcas.size());
  for (const auto& [id, t] : m.tcas) {
    EXPECT_EQ(t->material().name, "silver-nylon-castigliano");
    EXPECT_EQ(t->parameters().f12_form, tca::F12Form::kPaper);
    EXPECT_EQ(t->parameters().coiled_length_m, base.tcas.at(id)->parameters().coiled_length_m);
    EXPECT_EQ(t->parameters().twist_turns, base.tcas.at(id)->parameters().twist_turns);
  }
  for (const auto& a : m.actuators) {
    if (a.drive.type == Drive::Type::kTca) {
      EXPECT_EQ(a.drive.tca, m.tcas.at(a.drive.tca_id));
    }
  }
  // The original model is untouched, and without an f12 override the form is kept.
  EXPECT_EQ(base.tcas.begin()->second->material().name, "silver-nylon-sun2022");
  const RodModel kept = with_tca_material(base, other);
  EXPECT_EQ(kept.tcas.begin()->second->parameters().f12_form,
            base.tcas.begin()->second->parameters().f12_form);
}

// ---------------------------------------------------------------------------------------
// TCAs with a measured fiber diameter (docs/scenario-format.md "TCAs")

/// The full scenario with its gripper TCA given as the measured open-coil monocoil:
/// d0 = 0.74 mm, D = 2.372 mm (helix mean diameter 1.632 mm), L = 25 mm, 732 coils per metre.
json measured_gripper() {
  json doc = full();
  json& t = doc["tcas"]["gripper-tca"];
  t.erase("fiber_length_m");
  t["coiled_length_m"] = 0.025;
  t["outer_diameter_m"] = 2.372e-3;
  t["fiber_diameter_m"] = 0.74e-3;
  t["coils_per_m"] = 732;
  t["twist_turns"] = 47.3;
  return doc;
}

/// Geometry computed in double precision from the same inputs two ways.
constexpr double kGeometryRoundOff = 1e-12;

TEST(ParseScenario, MeasuredFiberDiameterWithCoilsPerMetreGivesTheHelix) {
  const RodModel m = parse_scenario(measured_gripper());
  const tca::Tca& t = *m.tcas.at("gripper-tca");
  const double Dm = 2.372e-3 - 0.74e-3, n = 732 * 0.025;
  EXPECT_EQ(t.initial_fiber_diameter_m(), 0.74e-3);
  EXPECT_NEAR(t.coil_count(), n, kGeometryRoundOff * n);
  EXPECT_NEAR(t.parameters().fiber_length_m, std::hypot(units::kPi * Dm * n, 0.025),
              kGeometryRoundOff);
  EXPECT_NEAR(t.closed_elongation_m(), n * 0.74e-3 - 0.025, kGeometryRoundOff);
  // The other ways of giving the same helix: coil_count; fiber length or pitch angle; both
  // (over-determined, agreeing within the stated tolerance).
  json doc = measured_gripper();
  doc["tcas"]["gripper-tca"].erase("coils_per_m");
  doc["tcas"]["gripper-tca"]["coil_count"] = n;
  EXPECT_NEAR(parse_scenario(doc).tcas.at("gripper-tca")->coil_count(), n, kGeometryRoundOff * n);
  doc["tcas"]["gripper-tca"]["coils_per_m"] = 732;
  doc["tcas"]["gripper-tca"]["fiber_length_m"] = 0.0971;  // three digits of l = 97.099 mm
  EXPECT_EQ(parse_scenario(doc).tcas.at("gripper-tca")->parameters().fiber_length_m, 0.0971);
  doc = measured_gripper();
  json& t2 = doc["tcas"]["gripper-tca"];
  t2.erase("coils_per_m");
  t2["pitch_angle_deg"] = units::rad_to_deg(std::atan(0.025 / (units::kPi * Dm * n)));
  EXPECT_NEAR(parse_scenario(doc).tcas.at("gripper-tca")->coil_count(), n, 1e-9 * n);
}

TEST(RejectScenario, OverDeterminedTcaGeometryThatDisagreesNamesBothKeys) {
  json doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["fiber_length_m"] = 0.09;  // 16.9 coils, not 18.3
  expect_rejected(doc, "tcas.gripper-tca.coils_per_m", "732", "disagrees with fiber_length_m");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["coil_count"] = 20;
  expect_rejected(doc, "tcas.gripper-tca.coils_per_m", "732", "disagrees with coil_count = 20");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["pitch_angle_deg"] = 20;
  expect_rejected(doc, "tcas.gripper-tca.coils_per_m", "732", "disagrees with pitch_angle_deg");
  // A fiber shorter than the coil is refused as such, not as a disagreement.
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["fiber_length_m"] = 0.02;
  expect_rejected(doc, "tcas.gripper-tca.coiled_length_m", "0.025",
                  "must be < fiber_length_m = 0.02");
}

TEST(RejectScenario, CoilCountWithoutMeasuredFiberDiameter) {
  json doc = full();
  doc["tcas"]["gripper-tca"]["coil_count"] = 150;
  expect_rejected(doc, "tcas.gripper-tca.coil_count", "150", "requires fiber_diameter_m");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"].erase("coils_per_m");
  expect_rejected(doc, "tcas.gripper-tca.fiber_length_m", "(missing)",
                  "pitch_angle_deg, coil_count or coils_per_m");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["fiber_diameter_m"] = "0.74 mm";
  expect_rejected(doc, "tcas.gripper-tca.fiber_diameter_m", "\"0.74 mm\"", "must be a number");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["coils_per_m"] = 0;
  expect_rejected(doc, "tcas.gripper-tca.coils_per_m", "0", "must be positive");
}

TEST(RejectScenario, ImpossibleMeasuredCoilGeometry) {
  json doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["fiber_diameter_m"] = 1.2e-3;
  expect_rejected(doc, "tcas.gripper-tca.fiber_diameter_m", "0.0012", "no coil");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["coils_per_m"] = 1500;  // pitch 0.67 mm < 0.74 mm
  expect_rejected(doc, "tcas.gripper-tca.fiber_diameter_m", "0.00074", "coils would overlap");
  doc = measured_gripper();
  doc["tcas"]["gripper-tca"]["twist_turns"] = 200;  // twist pitch 0.49 mm < 0.74 mm
  expect_rejected(doc, "tcas.gripper-tca.twist_turns", "200", "twist pitch");
  // Pre-elongated below its closed length n d0 = 13.5 mm (delta_c = -11.5 mm).
  doc = measured_gripper();
  doc["actuators"][1]["pre_elongation_m"] = -0.012;
  expect_rejected(doc, "actuators[1].pre_elongation_m", "-0.012", "cannot be shorter than closed");
}

}  // namespace
}  // namespace tcasim::rod
