// Obstacles (rod/obstacle.hpp): distances, section gaps and their variation, contact
// summaries, the scenario's `obstacles` and their refusals.
#include "rod/obstacle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"
#include "support/input_error.hpp"
#include "support/rod_models.hpp"

namespace tcasim::rod {
namespace {

using nlohmann::json;
using test_support::expect_input_error;

Obstacle plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  return test_support::plane_obstacle("floor", point, normal);
}

Obstacle sphere(const Eigen::Vector3d& centre, double r) {
  Obstacle o;
  o.name = "ball";
  o.type = Obstacle::Type::kSphere;
  o.point_W_m = centre;
  o.radius_m = r;
  return o;
}

Obstacle cylinder(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double r) {
  Obstacle o;
  o.name = "peg";
  o.type = Obstacle::Type::kCylinder;
  o.point_W_m = point;
  o.direction_W = axis.normalized();
  o.radius_m = r;
  return o;
}

Obstacle box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half,
             const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Obstacle o;
  o.name = "block";
  o.type = Obstacle::Type::kBox;
  o.point_W_m = centre;
  o.half_extents_m = half;
  o.R_WO = R;
  return o;
}

TEST(ObstacleDistance, ClosedFormsOfTheFourShapes) {
  const Obstacle p = plane({0, 0, 1}, {0, 0, 2});
  EXPECT_DOUBLE_EQ(p.distance({3, 4, 1.5}).distance_m, 0.5);
  EXPECT_DOUBLE_EQ(p.distance({3, 4, 0.5}).distance_m, -0.5);
  const Obstacle s = sphere({1, 0, 0}, 0.5);
  EXPECT_DOUBLE_EQ(s.distance({1, 2, 0}).distance_m, 1.5);
  EXPECT_TRUE(s.distance({1, 2, 0}).normal_W.isApprox(Eigen::Vector3d::UnitY()));
  const Obstacle c = cylinder({0, 0, 0}, {0, 0, 1}, 1.0);
  EXPECT_DOUBLE_EQ(c.distance({3, 4, 100}).distance_m, 4.0);
  EXPECT_TRUE(c.distance({3, 4, 100}).normal_W.isApprox(Eigen::Vector3d(0.6, 0.8, 0)));
  const Obstacle b = box({0, 0, 0}, {1, 2, 3});
  // Face, edge and corner regions outside, and the nearest face inside.
  EXPECT_DOUBLE_EQ(b.distance({2, 0, 0}).distance_m, 1.0);
  EXPECT_DOUBLE_EQ(b.distance({4, 6, 0}).distance_m, 5.0);
  EXPECT_TRUE(b.distance({4, 6, 0}).normal_W.isApprox(Eigen::Vector3d(0.6, 0.8, 0)));
  EXPECT_DOUBLE_EQ(b.distance({2, 3, 4}).distance_m, std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(b.distance({0.5, 0, 0}).distance_m, -0.5);
  EXPECT_TRUE(b.distance({0.5, 0, 0}).normal_W.isApprox(Eigen::Vector3d::UnitX()));
}

TEST(ObstacleDistance, RotatedBoxIsTheBoxInItsOwnAxes) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Obstacle b = box({1, -1, 2}, {0.3, 0.2, 0.1}, R);
  const Eigen::Vector3d y(0.9, -0.1, 0.05);  // in the box's axes: 0.6 beyond the x face
  const Obstacle::Distance d = b.distance(b.point_W_m + R * y);
  EXPECT_NEAR(d.distance_m, 0.6, 1e-15);
  EXPECT_TRUE(d.normal_W.isApprox(R.col(0), 1e-14));
}

TEST(ObstacleDistance, NormalIsTheGradientOfTheDistance) {
  const std::vector<Obstacle> shapes = {sphere({0.1, 0.2, 0.3}, 0.4),
                                        cylinder({0, 0, 0}, {1, 1, 0}, 0.2),
                                        box({0, 0, 0}, {0.3, 0.2, 0.1})};
  const std::vector<Eigen::Vector3d> points = {
      {0.9, 0.8, 0.7}, {0.05, 0.02, -0.01}, {-0.5, 0.6, 0.2}, {0.31, 0.21, 0.05}};
  const double h = 1e-6;
  for (const Obstacle& o : shapes) {
    for (const Eigen::Vector3d& x : points) {
      Eigen::Vector3d grad;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
        grad[i] = (o.distance(x + e).distance_m - o.distance(x - e).distance_m) / (2 * h);
      }
      // Central differences: O(h^2 / curvature radius) ~ 1e-11, round-off eps / h ~ 1e-10.
      EXPECT_LT((grad - o.distance(x).normal_W).norm(), 1e-8) << to_string(o.type);
    }
  }
}

TEST(SectionGap, CircleOnAPlaneIsTheLowestOutlinePoint) {
  const Obstacle floor = plane({0, 0, 0}, {0, 0, 1});
  const ContactOutline circle{ContactOutline::Kind::kCircle, 0.02, 0.02};
  // Horizontal rod along x at height 0.05: the lowest point is r below the centerline.
  Eigen::Matrix3d R;
  R << 0, 0, 1, 0, 1, 0, -1, 0, 0;  // body e3 along world x
  const SectionGap g = section_gap(floor, circle, {0, 0, 0.05}, R);
  EXPECT_NEAR(g.gap_m, 0.04, 1e-16);
  EXPECT_TRUE(g.offset_W_m.isApprox(Eigen::Vector3d(0, 0, -0.01)));
  // Tilted by 30 degrees about y: the section's lowest point is r cos(30 deg) below.
  const Eigen::Matrix3d Rt = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitY()).matrix() * R;
  EXPECT_NEAR(section_gap(floor, circle, {0, 0, 0.05}, Rt).gap_m, 0.05 - 0.01 * std::cos(M_PI / 6),
              1e-16);
}

TEST(SectionGap, RectangleOnAPlaneHasItsFourCornersAndNoEdgePoints) {
  const Obstacle floor = plane({0, 0, 0}, {0, 0, 1});
  const ContactOutline rect{ContactOutline::Kind::kRectangle, 0.04, 0.02};
  // Body x along world z, rotated 10 degrees about the rod axis (world x).
  Eigen::Matrix3d R;
  R << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  R = Eigen::AngleAxisd(0.1745, Eigen::Vector3d::UnitX()).matrix() * R;
  const auto gaps = section_gaps(floor, rect, {0, 0, 0.1}, R);
  ASSERT_EQ(gaps.size(), 8u);
  ASSERT_EQ(contact_candidate_count(ContactOutline::Kind::kRectangle), 8);
  double lowest = 1.0;
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(gaps[j].gap_m, 0.1 + gaps[j].offset_W_m.z(), 1e-16);
    lowest = std::min(lowest, gaps[j].gap_m);
  }
  for (int j = 4; j < 8; ++j) EXPECT_TRUE(std::isinf(gaps[j].gap_m));
  EXPECT_EQ(section_gap(floor, rect, {0, 0, 0.1}, R).gap_m, lowest);
}

TEST(SectionGap, FaceOfARectangleTouchesACylinderInsideItsEdge) {
  // A rod lying along a cylinder (axis world y) with its flat face (width 0.04 along world x)
  // down: the face's middle touches, the corners are higher.
  const Obstacle peg = cylinder({0, 0, 0}, {0, 1, 0}, 0.1);
  const ContactOutline rect{ContactOutline::Kind::kRectangle, 0.04, 0.02};
  Eigen::Matrix3d R;  // body x = world x, body y = world z, body e3 = x x z = -world y
  R.col(0) = Eigen::Vector3d::UnitX();
  R.col(1) = Eigen::Vector3d::UnitZ();
  R.col(2) = R.col(0).cross(R.col(1));
  const double height = 0.1 + 0.01 + 0.003;  // the face 3 mm above the top of the peg
  const SectionGap g = section_gap(peg, rect, {0, 0, height}, R);
  // Golden-section search to ~1e-15 of the edge; the distance is quadratic in the position
  // there, so the gap is exact to round-off.
  EXPECT_NEAR(g.gap_m, 0.003, 1e-14);
  EXPECT_NEAR(g.offset_W_m.z(), -0.01, 1e-15);
  EXPECT_NEAR(g.offset_W_m.x(), 0.0, 1e-7);
  // Across the cylinder (rod along world x) the distance is constant along the bottom edge:
  // its two corners hold the contact and the edge has no candidate.
  Eigen::Matrix3d C;
  C.col(0) = Eigen::Vector3d::UnitY();
  C.col(1) = Eigen::Vector3d::UnitZ();
  C.col(2) = C.col(0).cross(C.col(1));
  const auto across = section_gaps(peg, rect, {0, 0, height}, C);
  for (int j = 4; j < 8; ++j) EXPECT_TRUE(std::isinf(across[j].gap_m));
  EXPECT_NEAR(section_gap(peg, rect, {0, 0, height}, C).gap_m, 0.003, 1e-15);
}

TEST(SectionGap, VariationIsNormalDisplacementAndMomentOfTheTouchingPoint) {
  // dg = n . dp + (c x n) . dtheta for a circle with n in the section plane (here a rod
  // lying across a sphere) and for any corner.
  const Obstacle ball = sphere({0, 0, 0}, 0.3);
  const ContactOutline circle{ContactOutline::Kind::kCircle, 0.02, 0.02};
  Eigen::Matrix3d R;
  R << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  const Eigen::Vector3d p(0, 0, 0.35);
  const SectionGap g = section_gap(ball, circle, p, R);
  const double h = 1e-7;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(i);
    const double dp =
        (section_gap(ball, circle, p + e, R).gap_m - section_gap(ball, circle, p - e, R).gap_m) /
        (2 * h);
    EXPECT_NEAR(dp, g.normal_W[i], 1e-7);
    const Eigen::Matrix3d Rp = Eigen::AngleAxisd(h, Eigen::Vector3d::Unit(i)).matrix() * R;
    const Eigen::Matrix3d Rm = Eigen::AngleAxisd(-h, Eigen::Vector3d::Unit(i)).matrix() * R;
    const double dth =
        (section_gap(ball, circle, p, Rp).gap_m - section_gap(ball, circle, p, Rm).gap_m) / (2 * h);
    EXPECT_NEAR(dth, g.offset_W_m.cross(g.normal_W)[i], 1e-7);
  }
}

TEST(ContactSummary, RegionsAreRunsOfTouchingSectionsAndMomentsAreAboutTheBase) {
  const Obstacle floor = plane({0, 0, 0}, {0, 0, 1});
  std::vector<ContactSample> samples;
  const auto add = [&](double s, double f, double gap) {
    samples.push_back({s, {s, 0, 0}, {0, 0, f}, gap});
  };
  add(0.1, 0.0, 0.01);
  add(0.2, 1.0, 0.0);
  add(0.3, 2.0, -1e-9);
  add(0.4, 0.0, 0.002);
  add(0.5, 0.5, 0.0);
  const ContactResult r = summarize_contact(floor, samples, {0, 0, 0});
  ASSERT_EQ(r.regions.size(), 2u);
  EXPECT_EQ(r.regions[0].s0_m, 0.2);
  EXPECT_EQ(r.regions[0].s1_m, 0.3);
  EXPECT_EQ(r.regions[0].force_W_N.z(), 3.0);
  EXPECT_EQ(r.regions[1].s0_m, 0.5);
  EXPECT_EQ(r.regions[1].s1_m, 0.5);
  EXPECT_EQ(r.force_W_N.z(), 3.5);
  EXPECT_NEAR(r.moment_W_Nm.y(), -(0.2 * 1.0 + 0.3 * 2.0 + 0.5 * 0.5), 1e-15);
  EXPECT_EQ(r.max_penetration_m, 1e-9);
  EXPECT_TRUE(r.in_contact());
}

// --- Scenario files ---

json rod_with(const json& obstacles) {
  json doc = json::parse(R"({
    "schema": "tcasim.scenario/1", "name": "rod-on-floor",
    "body": {"length_m": 1.0, "section": {"shape": "circle", "diameter_m": 0.002},
             "material": {"youngs_modulus_Pa": 2e11, "poisson_ratio": 0.3}},
    "base": {"position_m": [0, 0, 0.01], "rotation": [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]}
  })");
  doc["obstacles"] = obstacles;
  return doc;
}

// A rod whose centerline samples (its contact points) straddle a small sphere: clear at every
// sample, but the polyline between two of them runs through the sphere. A converged result is
// marked as passing between its contact points, naming the obstacle; a sphere the chord only
// grazes (a wrapped rod's sagitta) is reported as a depth and left converged.
TEST(BetweenContactPoints, ARodThroughASmallSphereBetweenTwoPointsIsNotConverged) {
  RodModel m = test_support::circular_rod(1.0, 0.002, 200e9, 0.3, 7850.0);
  Result r;
  r.converged = true;
  r.status = "converged";
  for (int k = 0; k <= 10; ++k) {
    r.centerline_s_m.push_back(0.1 * k);
    r.centerline_p_W_m.emplace_back(0.1 * k, 0.0, 0.0);
  }
  m.obstacles = {sphere(Eigen::Vector3d(0.55, 0.0, -0.003), 0.01)};  // nodes 0.5, 0.6: clear
  r.contacts.resize(1);
  ASSERT_GT(m.obstacles[0].distance(Eigen::Vector3d(0.5, 0, 0)).distance_m, 0.001);
  check_between_contact_points(m, r);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, "passes_between_contact_points");
  EXPECT_NE(r.message.find("obstacles[0] \"ball\""), std::string::npos) << r.message;
  EXPECT_NEAR(r.contacts[0].core_penetration_s_m, 0.55, 1e-12);
  // Core inscribed circle r = 1 mm: depth = 1 mm - (3 mm - 10 mm) = 8 mm.
  EXPECT_NEAR(r.contacts[0].core_penetration_between_m, 0.008, 1e-12);

  // Grazing: the core 0.4 mm inside (less than half the 1 mm inradius).
  Result g = r;
  g.converged = true;
  g.status = "converged";
  g.message.clear();
  m.obstacles = {sphere(Eigen::Vector3d(0.55, 0.0, -0.0106), 0.01)};
  check_between_contact_points(m, g);
  EXPECT_TRUE(g.converged);
  EXPECT_EQ(g.status, "converged");
  EXPECT_NEAR(g.contacts[0].core_penetration_between_m, 0.0004, 1e-12);
}

TEST(ScenarioObstacles, ReadsTheFourShapes) {
  const RodModel m = parse_scenario(rod_with(json::parse(R"([
    {"name": "floor", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 2]},
    {"name": "peg", "type": "cylinder", "point_m": [0.5, 0, 0.5], "axis": [0, 3, 0],
     "radius_m": 0.1, "friction": 0.4},
    {"name": "ball", "type": "sphere", "center_m": [0.5, 0, -0.5], "radius_m": 0.2},
    {"name": "block", "type": "box", "center_m": [2, 0, 0], "half_extents_m": [0.1, 0.2, 0.3],
     "rotation": [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}
  ])")));
  ASSERT_EQ(m.obstacles.size(), 4u);
  EXPECT_EQ(m.obstacles[0].type, Obstacle::Type::kPlane);
  EXPECT_TRUE(m.obstacles[0].direction_W.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_EQ(m.obstacles[1].friction, 0.4);
  EXPECT_TRUE(m.obstacles[1].direction_W.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(m.obstacles[2].radius_m, 0.2);
  EXPECT_EQ(m.obstacles[3].R_WO(1, 2), -1.0);
}

TEST(ScenarioObstacles, RefusesDegenerateShapesByKey) {
  const auto refused = [](const char* text, const std::string& key, const std::string& rule) {
    expect_input_error([&] { (void)parse_scenario(rod_with(json::parse(text))); }, key, rule);
  };
  refused(R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 0]}])",
          "obstacles[0].normal", "non-zero");
  refused(R"([{"name": "b", "type": "sphere", "center_m": [0, 0, -1], "radius_m": 0}])",
          "obstacles[0].radius_m", "positive");
  refused(R"([{"name": "b", "type": "box", "center_m": [5, 0, 0], "half_extents_m": [1, 0, 1]}])",
          "obstacles[0].half_extents_m[1]", "positive");
  refused(R"([{"name": "b", "type": "box", "center_m": [5, 0, 0], "half_extents_m": [1, 1, 1],
               "rotation": [[1, 0, 0], [0, 1, 0], [0, 0.5, 1]]}])",
          "obstacles[0].rotation", "orthonormal");
  refused(R"([{"name": "f", "type": "wall", "point_m": [0, 0, 0]}])", "obstacles[0].type",
          "must be one of");
  refused(R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 1],
               "radius_m": 1}])",
          "obstacles[0].radius_m", "not an allowed key");
  refused(R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 1]},
              {"name": "f", "type": "plane", "point_m": [0, 0, -1], "normal": [0, 0, 1]}])",
          "obstacles[1].name", "not unique");
  refused(R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 1],
               "friction": -0.1}])",
          "obstacles[0].friction", ">= 0");
}

TEST(ScenarioObstacles, RefusesAnObstacleHoldingTheBaseOrPenetratedAtRest) {
  // The base at z = 0.01 lies below a floor at z = 0.02.
  expect_input_error(
      [] {
        (void)parse_scenario(rod_with(json::parse(
            R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0.02], "normal": [0, 0, 1]}])")));
      },
      "obstacles[0]", "base");
  // A ball across the straight rod at x = 0.5: its section there is inside.
  try {
    (void)parse_scenario(rod_with(json::parse(
        R"([{"name": "ball", "type": "sphere", "center_m": [0.5, 0, 0.0], "radius_m": 0.0105}])")));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "obstacles[0]");
    EXPECT_NE(e.rule().find("s = 0.49"), std::string::npos) << e.what();
  }
  // The rod's lowest line exactly on the floor is allowed (gap 0 at rest).
  const RodModel m = parse_scenario(rod_with(json::parse(
      R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0.009], "normal": [0, 0, 1]}])")));
  EXPECT_EQ(m.obstacles.size(), 1u);
}

TEST(ScenarioObstacles, CustomSectionNeedsAContactRadius) {
  json doc = rod_with(json::parse(
      R"([{"name": "f", "type": "plane", "point_m": [0, 0, 0], "normal": [0, 0, 1]}])"));
  doc["body"]["section"] = json::parse(
      R"({"shape": "custom", "area_m2": 1e-6, "I_x_m4": 1e-12, "I_y_m4": 1e-12, "J_m4": 2e-12})");
  expect_input_error([&] { (void)parse_scenario(doc); }, "body.section.contact_radius_m",
                     "required");
  doc["body"]["section"]["contact_radius_m"] = 0.001;
  const RodModel m = parse_scenario(doc);
  const ContactOutline o = contact_outline_at(m, 0.3);
  EXPECT_EQ(o.kind, ContactOutline::Kind::kCircle);
  EXPECT_EQ(o.width_m, 0.002);
}

}  // namespace
}  // namespace tcasim::rod
