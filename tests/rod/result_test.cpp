// Result file serialization and the paper's three-point inner-edge radius metric.
#include "rod/result.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// The arc samples are exact to round-off; the circumradius of points ~L apart with
/// radius ~R loses about R/L digits more.
constexpr double kRadiusRelative = 1e-11;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

Result sample_result() {
  Result r;
  r.scenario = "rod-test";
  r.method = "fe";
  r.discretization = {{"elements", 32}, {"order", 2}, {"tolerance", 1e-8}};
  r.converged = true;
  r.iterations = 5;
  r.status = "converged";
  r.residual = 3.1e-13;
  r.characteristic_force_N = 0.0047;
  r.wall_time_s = 0.0004;
  r.tip_position_W_m = {0.01, -0.002, 0.035};
  // Not symmetric, so a transposed writer fails.
  r.tip_R_WB = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  r.actuators.resize(2);
  r.actuators[0].name = "tca";
  r.actuators[0].tension_N = -0.0031;
  r.actuators[0].elongation_m = 0.0002;
  r.actuators[1].name = "tendon";
  r.actuators[1].tension_N = 0.5;
  r.actuators[1].elongation_m = -1e-5;
  r.bending_radius_m = 0.052;
  r.centerline_s_m = {0.0, 0.02, 0.04};
  r.centerline_p_W_m = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.001, 0, 0.02),
                        Eigen::Vector3d(0.01, -0.002, 0.035)};
  r.centerline_R_WB.assign(3, Eigen::Matrix3d::Identity());
  return r;
}

TEST(ResultJson, ADefaultResultSaysNoSolveRanAndAnUnevaluatedResidualIsNull) {
  const Result none;
  EXPECT_EQ(none.status, "not_run");
  EXPECT_FALSE(none.residual.has_value());
  const json j = to_json(none);
  EXPECT_EQ(j.at("status"), "not_run");
  EXPECT_TRUE(j.at("residual").is_null());
  EXPECT_FALSE(j.at("converged").get<bool>());
  // "Not evaluated" is not a non-finite value: no note about one.
  EXPECT_EQ(j.at("message").get<std::string>().find("non-finite"), std::string::npos);
}

TEST(ResultJson, AConvergedResultWithANonFiniteNumberIsNotReportedConverged) {
  Result r = sample_result();
  r.tip_position_W_m.x() = std::numeric_limits<double>::quiet_NaN();
  const json j = to_json(r);
  EXPECT_FALSE(j.at("converged").get<bool>());
  EXPECT_EQ(j.at("status"), "non_finite_result");
}

TEST(ResultJson, WritesEveryFieldOfTheFormatAndRoundTripsThroughText) {
  const Result r = sample_result();
  // Through text: the written numbers must read back bit-exact.
  const json j = json::parse(to_json(r).dump(2));
  EXPECT_EQ(j.at("schema"), "tcasim.result/1");
  EXPECT_EQ(j.at("scenario"), "rod-test");
  EXPECT_EQ(j.at("method"), "fe");
  EXPECT_TRUE(j.at("discretization").at("elements").is_number_integer());
  EXPECT_EQ(j.at("discretization").at("elements"), 32);
  EXPECT_EQ(j.at("discretization").at("order"), 2);
  EXPECT_EQ(j.at("discretization").at("tolerance").get<double>(), 1e-8);
  EXPECT_EQ(j.at("converged"), true);
  EXPECT_FALSE(j.contains("message"));
  EXPECT_EQ(j.at("iterations"), 5);
  EXPECT_EQ(j.at("residual").get<double>(), 3.1e-13);
  EXPECT_EQ(j.at("status"), "converged");
  EXPECT_EQ(j.at("characteristic_force_N").get<double>(), 0.0047);
  EXPECT_EQ(j.at("wall_time_s").get<double>(), 0.0004);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(j.at("tip").at("position_m").at(i).get<double>(), r.tip_position_W_m[i]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(j.at("tip").at("rotation").at(i).at(c).get<double>(), r.tip_R_WB(i, c))
          << "row-major: rotation[" << i << "][" << c << "]";
    }
  }
  ASSERT_EQ(j.at("actuators").size(), 2u);
  EXPECT_EQ(j.at("actuators")[1].at("name"), "tendon");
  EXPECT_EQ(j.at("actuators")[0].at("tension_N").get<double>(), -0.0031);
  EXPECT_EQ(j.at("actuators")[1].at("elongation_m").get<double>(), -1e-5);
  EXPECT_EQ(j.at("bending_radius_m").get<double>(), 0.052);
  EXPECT_EQ(j.at("centerline").at("s_m").get<std::vector<double>>(), r.centerline_s_m);
  EXPECT_EQ(j.at("centerline").at("position_m")[1].get<std::vector<double>>(),
            (std::vector<double>{0.001, 0, 0.02}));
  EXPECT_FALSE(j.contains("tip_reaction_force_N"));  // no tip constraint
}

TEST(ResultJson, StraightRodHasNullRadiusAndConstraintAddsTheReaction) {
  Result r = sample_result();
  r.bending_radius_m.reset();
  r.tip_reaction_force_W_N = Eigen::Vector3d(0.1, -0.2, 0.3);
  const json j = to_json(r);
  ASSERT_TRUE(j.contains("bending_radius_m"));
  EXPECT_TRUE(j.at("bending_radius_m").is_null());
  EXPECT_EQ(j.at("tip_reaction_force_N").get<std::vector<double>>(),
            (std::vector<double>{0.1, -0.2, 0.3}));
}

TEST(ResultJson, NotConvergedResultCarriesItsMessage) {
  Result r = sample_result();
  r.converged = false;
  r.message = "Newton stalled: ||r|| = 1e-3 after 50 iterations";
  json j = to_json(r);
  EXPECT_EQ(j.at("converged"), false);
  EXPECT_EQ(j.at("message"), r.message);
  r.message.clear();
  j = to_json(r);
  EXPECT_TRUE(j.at("message").is_string());
  EXPECT_FALSE(j.at("message").get<std::string>().empty());
}

TEST(ResultJson, NonFiniteValueBecomesNullAndMarksTheResultNotConverged) {
  Result r = sample_result();
  r.actuators[1].tension_N = std::numeric_limits<double>::quiet_NaN();
  r.centerline_p_W_m[2].y() = std::numeric_limits<double>::infinity();
  const std::string text = to_json(r).dump();
  EXPECT_FALSE(contains(text, "nan") || contains(text, "NaN") || contains(text, "inf"));
  const json j = json::parse(text);
  EXPECT_EQ(j.at("converged"), false);
  EXPECT_TRUE(j.at("actuators")[1].at("tension_N").is_null());
  EXPECT_TRUE(j.at("centerline").at("position_m")[2][1].is_null());
  const std::string message = j.at("message");
  EXPECT_TRUE(contains(message, "actuators[1].tension_N")) << message;
  EXPECT_TRUE(contains(message, "centerline.position_m[2][1]")) << message;

  // A message the solver gave is kept.
  r.converged = false;
  r.message = "diverged";
  EXPECT_TRUE(contains(to_json(r).at("message").get<std::string>(), "diverged; non-finite"));
}

TEST(FormatJson, PutsScalarArraysOnOneLineAndParsesBack) {
  const json small = {{"p", {1.5, -2.0, 3.0}},
                      {"m", {{1, 0}, {0, 1}}},
                      {"e", json::array()},
                      {"o", json::object()},
                      {"s", "x"}};
  EXPECT_EQ(format_json(small),
            "{\n  \"e\": [],\n  \"m\": [\n    [1, 0],\n    [0, 1]\n  ],\n  \"o\": {},\n"
            "  \"p\": [1.5, -2.0, 3.0],\n  \"s\": \"x\"\n}");
  const json j = to_json(sample_result());
  EXPECT_EQ(json::parse(format_json(j)), j);
}

TEST(WriteResult, WritesAFileOrStdoutAndNamesAnUnwritablePath) {
  const Result r = sample_result();
  const auto path =
      (std::filesystem::temp_directory_path() / "tcasim_rod_test_result.json").string();
  write_result(r, path);
  std::ifstream in(path);
  EXPECT_EQ(json::parse(in), json::parse(to_json(r).dump()));
  std::filesystem::remove(path);

  testing::internal::CaptureStdout();
  write_result(r, "-");
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(json::parse(out), json::parse(to_json(r).dump()));

  const std::string bad = "/nonexistent-dir/result.json";
  try {
    write_result(r, bad);
    ADD_FAILURE() << "wrote to " << bad;
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), bad)) << e.what();
  }
}

// ---------------------------------------------------------------------------------------
// Radius metric

/// A rod bent into a circular arc of radius R toward body direction u = (cos beta,
/// sin beta) (constant strains nu = e3, omega = (e3 x u)/R), sampled at n points, with
/// the base at p0 with frame R0.
struct Arc {
  std::vector<double> s;
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Matrix3d> R;
};

Arc make_arc(double radius_m, double length_m, double beta_rad, int n, const Eigen::Vector3d& p0,
             const Eigen::Matrix3d& R0) {
  const Eigen::Vector3d u(std::cos(beta_rad), std::sin(beta_rad), 0.0);
  const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(u);
  Arc a;
  for (int i = 0; i < n; ++i) {
    const double s = length_m * i / (n - 1);
    const double th = s / radius_m;
    a.s.push_back(s);
    a.p.push_back(p0 + R0 * (radius_m * (1.0 - std::cos(th)) * u +
                             radius_m * std::sin(th) * Eigen::Vector3d::UnitZ()));
    a.R.push_back(R0 * Eigen::AngleAxisd(th, axis).toRotationMatrix());
  }
  return a;
}

RodModel circle_body(double d, double length_m) {
  RodModel m;
  m.length_m = length_m;
  m.section.shape = Section::Shape::kCircle;
  m.section.width_profile = Profile(d);
  m.section.height_profile = Profile(d);
  return m;
}

TEST(ThreePointRadius, CircularArcGivesRadiusMinusHalfWidthWithSampleAtMiddle) {
  const double R = 0.05, L = 0.04, D = 0.008;
  const Arc a = make_arc(R, L, 0.0, 9, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  const auto r = three_point_inner_radius(circle_body(D, L), a.s, a.p, a.R);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r / (R - D / 2.0), 1.0, kRadiusRelative);
}

TEST(ThreePointRadius, CircularArcGivesRadiusMinusHalfWidthWithMiddleInterpolated) {
  // 8 samples: L/2 falls between samples 3 and 4; constant-strain interpolation is exact.
  const double R = 0.03, L = 0.04, D = 0.008;
  for (const int n : {2, 4, 8}) {
    const Arc a = make_arc(R, L, 2.0, n, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    const auto r = three_point_inner_radius(circle_body(D, L), a.s, a.p, a.R);
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(*r / (R - D / 2.0), 1.0, kRadiusRelative) << n << " samples";
  }
}

TEST(ThreePointRadius, RectangleBentDiagonallyWithMovedBaseUsesTheEdgeAlongTheDirection) {
  const double R = 0.04, L = 0.05, w = 0.010, h = 0.004;
  RodModel m = circle_body(0.0, L);
  m.section.shape = Section::Shape::kRectangle;
  m.section.width_profile = Profile(w);
  m.section.height_profile = Profile(h);
  const double beta = units::kPi / 4.0;
  // Toward 45 degrees the top edge (y = h/2) is met first: h/2 * sqrt(2) from the centerline.
  const double half_extent = 0.5 * h * std::sqrt(2.0);
  const Eigen::Matrix3d R0 =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(-1, 0.5, 2).normalized()).toRotationMatrix();
  const Arc a = make_arc(R, L, beta, 7, Eigen::Vector3d(0.3, -0.1, 2.0), R0);
  const auto r = three_point_inner_radius(m, a.s, a.p, a.R);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r / (R - half_extent), 1.0, kRadiusRelative);
  // Along x the half extent would be w/2: a different value, so the direction matters.
  EXPECT_GT(std::abs(*r - (R - 0.5 * w)), 1e-3);
}

TEST(ThreePointRadius, ArcTurningBeyondAHalfCircleStillUsesTheInnerEdge) {
  // Turning angle 1.5 pi: the chord still points toward the centre of curvature.
  const double R = 0.01, L = 1.5 * units::kPi * R, D = 0.004;
  const Arc a = make_arc(R, L, -0.7, 31, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  const auto r = three_point_inner_radius(circle_body(D, L), a.s, a.p, a.R);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r / (R - D / 2.0), 1.0, kRadiusRelative);
}

TEST(ThreePointRadius, StraightRodAndCustomSectionHaveNoRadius) {
  const double L = 0.04;
  Arc a;
  for (int i = 0; i < 5; ++i) {
    a.s.push_back(L * i / 4);
    a.p.push_back(Eigen::Vector3d(0, 0, L * i / 4));
    a.R.push_back(Eigen::Matrix3d::Identity());
  }
  EXPECT_FALSE(three_point_inner_radius(circle_body(0.008, L), a.s, a.p, a.R).has_value());
  // A uniformly compressed straight rod: still none.
  for (auto& p : a.p) p *= 0.9;
  EXPECT_FALSE(three_point_inner_radius(circle_body(0.008, L), a.s, a.p, a.R).has_value());

  const Arc bent = make_arc(0.05, L, 0.0, 5, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  RodModel custom = circle_body(0.008, L);
  custom.section.shape = Section::Shape::kCustom;
  EXPECT_FALSE(three_point_inner_radius(custom, bent.s, bent.p, bent.R).has_value());
}

}  // namespace
}  // namespace tcasim::rod

namespace tcasim::rod {
namespace {

TEST(SetCoilContacts, ClosedBelowTheBlockedForceWithItsContactForceAndWritesBoth) {
  const std::filesystem::path file = std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" /
                                     "scenarios" / "square-manipulator.json";
  RodModel model = read_scenario(file.string());
  const Actuator& act = model.actuators.at(0);
  const double t_K = act.drive.segments.at(0).temperature_K;
  const double blocked_N = act.drive.tca->blocked_force(t_K);  // F at delta = 0
  ActuatorResult a;
  a.name = act.name;
  a.tension_N = blocked_N - 1e-3;
  set_coil_contacts(act, act.drive.segments, a);
  EXPECT_TRUE(a.coils_closed);
  EXPECT_NEAR(a.contact_force_N, 1e-3, 1e-12);  // c = F_b - F
  Result result;
  result.actuators.push_back(a);
  EXPECT_EQ(to_json(result)["actuators"][0]["coils_closed"], true);
  EXPECT_NEAR(to_json(result)["actuators"][0]["contact_force_N"].get<double>(), 1e-3, 1e-12);

  a.tension_N = blocked_N + 1e-3;
  set_coil_contacts(act, act.drive.segments, a);
  EXPECT_FALSE(a.coils_closed);
  EXPECT_EQ(a.contact_force_N, 0.0);
  result.actuators[0] = a;
  EXPECT_EQ(to_json(result)["actuators"][0]["coils_closed"], false);
}

TEST(SetCoilContacts, SegmentedTcaReportsEachSegmentAndTensionDrivesNothing) {
  const std::filesystem::path file =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" / "segmented-tca.json";
  RodModel model = read_scenario(file.string());
  const Actuator& act = model.actuators.at(0);
  ASSERT_TRUE(act.drive.segmented);
  ASSERT_GE(act.drive.segments.size(), 2u);
  std::vector<tca::Segment> segs = act.drive.segments;
  segs[0].temperature_K = 298.15;  // cold: high blocked force
  segs[1].temperature_K = 403.15;  // hot: low blocked force
  const double fb0 = act.drive.tca->blocked_force(segs[0].temperature_K);
  const double fb1 = act.drive.tca->blocked_force(segs[1].temperature_K);
  ASSERT_GT(fb0, fb1);
  ActuatorResult a;
  a.tension_N = 0.5 * (fb0 + fb1);  // between: segment 0 closed, segment 1 open
  set_coil_contacts(act, segs, a);
  ASSERT_EQ(a.segments.size(), segs.size());
  EXPECT_TRUE(a.segments[0].second.coils_closed);
  EXPECT_NEAR(a.segments[0].second.contact_force_N, fb0 - a.tension_N, 1e-12 * std::abs(fb0));
  EXPECT_FALSE(a.segments[1].second.coils_closed);
  EXPECT_TRUE(a.coils_closed);  // some coils closed
  Result result;
  result.actuators.push_back(a);
  const auto j = to_json(result)["actuators"][0]["segments"];
  ASSERT_EQ(j.size(), segs.size());
  EXPECT_EQ(j[0]["coils_closed"], true);
  EXPECT_EQ(j[1]["coils_closed"], false);

  Actuator tendon;
  tendon.drive.type = Drive::Type::kTension;
  ActuatorResult t;
  set_coil_contacts(tendon, {}, t);
  EXPECT_FALSE(t.is_tca);
  result.actuators[0] = t;
  EXPECT_FALSE(to_json(result)["actuators"][0].contains("coils_closed"));
}

}  // namespace
}  // namespace tcasim::rod
