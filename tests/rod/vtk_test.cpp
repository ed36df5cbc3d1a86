// Shape output: VTK XML PolyData (.vtp) and the shape CSV of a result.
#include "rod/vtk.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace tcasim::rod {
namespace {

/// Numbers are written with 17 significant digits: they must read back bit-exact.
constexpr double kExact = 0.0;
/// q - p = R r recomputed from parsed numbers: one rounding of each sum, relative to |p| ~ 0.05 m.
constexpr double kOffsetAbs_m = 1e-16;

RodModel sample_model() {
  RodModel m;
  m.name = "vtk-test";
  m.length_m = 0.04;
  Actuator a;
  a.name = "tca-left";
  a.routing.type = Routing::Type::kStraight;
  a.routing.offset_m = {0.003, -0.001};
  a.count = 2;  // two parallel strings at one place: one path
  m.actuators.push_back(a);
  Actuator h;
  h.name = "helix";
  h.routing.type = Routing::Type::kHelix;
  h.routing.radius_m = 0.002;
  h.routing.phase_rad = 0.4;
  h.routing.turns_per_m = 25.0;
  m.actuators.push_back(h);
  return m;
}

Result sample_result(int samples) {
  Result r;
  r.scenario = "vtk-test";
  r.method = "cosserat";
  for (int k = 0; k < samples; ++k) {
    const double s = 0.04 * k / (samples - 1);
    r.centerline_s_m.push_back(s);
    // A bent, twisted centerline: non-trivial positions and rotations.
    r.centerline_p_W_m.emplace_back(0.1 * s * s + 1e-3 / 3.0, -0.3 * s * s, s);
    r.centerline_R_WB.push_back(
        Eigen::AngleAxisd(20.0 * s, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix());
  }
  return r;
}

/// Text between <DataArray ... Name="name" ...> and </DataArray>.
std::string data_array(const std::string& doc, const std::string& name) {
  const std::regex re("<DataArray[^>]*Name=\"" + name + "\"[^>]*>([^<]*)</DataArray>");
  std::smatch m;
  if (!std::regex_search(doc, m, re)) return "<missing " + name + ">";
  return m[1].str();
}

std::string attribute(const std::string& doc, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(doc, m, std::regex(name + "=\"([^\"]*)\""))) return "";
  return m[1].str();
}

template <typename T>
std::vector<T> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<T> out;
  T v;
  while (in >> v) out.push_back(v);
  return out;
}

/// Decodes a VTK ASCII String array (byte codes, each string terminated by 0).
std::vector<std::string> strings(const std::string& text) {
  std::vector<std::string> out(1);
  for (int c : numbers<int>(text)) {
    if (c == 0) {
      out.emplace_back();
    } else {
      out.back() += static_cast<char>(c);
    }
  }
  out.pop_back();
  return out;
}

/// True if every element opened is closed in order (an XML well-formedness check of tags).
bool tags_balanced(const std::string& doc) {
  const std::regex tag("<(/?)([A-Za-z][A-Za-z0-9]*)[^>]*?(/?)>");
  std::vector<std::string> stack;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), tag); it != std::sregex_iterator();
       ++it) {
    const auto& m = *it;
    if (m[3].length() > 0) continue;  // self-closing
    if (m[1].length() == 0) {
      stack.push_back(m[2].str());
    } else {
      if (stack.empty() || stack.back() != m[2].str()) return false;
      stack.pop_back();
    }
  }
  return stack.empty();
}

TEST(Vtp, HasOnePolylinePerCurveWithCountsAndOffsetsThatMatch) {
  const RodModel model = sample_model();
  const Result result = sample_result(9);
  const std::string doc = vtp_document(model, result);
  EXPECT_TRUE(tags_balanced(doc));
  EXPECT_NE(doc.find("<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\""),
            std::string::npos);
  // Centerline + 2 actuators (the count-2 actuator is one path), 9 points each.
  EXPECT_EQ(attribute(doc, "NumberOfPoints"), "27");
  EXPECT_EQ(attribute(doc, "NumberOfLines"), "3");
  EXPECT_EQ(numbers<long>(data_array(doc, "offsets")), (std::vector<long>{9, 18, 27}));
  std::vector<long> expected_connectivity(27);
  for (long k = 0; k < 27; ++k) expected_connectivity[k] = k;
  EXPECT_EQ(numbers<long>(data_array(doc, "connectivity")), expected_connectivity);
  EXPECT_EQ(numbers<double>(data_array(doc, "Points")).size(), 81u);
}

TEST(Vtp, PointDataAndFieldDataReadBack) {
  const RodModel model = sample_model();
  const Result result = sample_result(5);
  const std::string doc = vtp_document(model, result);
  const auto ids =
      numbers<int>(data_array(doc, "actuator_id"));  // the point data array comes first
  EXPECT_EQ(ids, (std::vector<int>{-1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
  const auto s = numbers<double>(data_array(doc, "s_m"));
  ASSERT_EQ(s.size(), 15u);
  for (std::size_t k = 0; k < s.size(); ++k) EXPECT_EQ(s[k], result.centerline_s_m[k % 5]);
  EXPECT_EQ(strings(data_array(doc, "scenario")), std::vector<std::string>{"vtk-test"});
  EXPECT_EQ(strings(data_array(doc, "method")), std::vector<std::string>{"cosserat"});
  EXPECT_EQ(strings(data_array(doc, "curve_names")),
            (std::vector<std::string>{"centerline", "tca-left", "helix"}));
}

TEST(Vtp, CenterlinePointsReadBackBitExactAndActuatorOffsetsEqualRTimesR) {
  const RodModel model = sample_model();
  const Result result = sample_result(7);
  const auto xyz = numbers<double>(data_array(vtp_document(model, result), "Points"));
  ASSERT_EQ(xyz.size(), 3u * 7u * 3u);
  auto point = [&](std::size_t curve, std::size_t k) {
    const std::size_t i = 3 * (7 * curve + k);
    return Eigen::Vector3d(xyz[i], xyz[i + 1], xyz[i + 2]);
  };
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_LE((point(0, k) - result.centerline_p_W_m[k]).cwiseAbs().maxCoeff(), kExact) << k;
    for (std::size_t a = 0; a < 2; ++a) {
      const Eigen::Vector3d offset = point(a + 1, k) - point(0, k);
      const Eigen::Vector3d expected =
          result.centerline_R_WB[k] * model.actuators[a].routing.r(result.centerline_s_m[k]);
      EXPECT_LE((offset - expected).cwiseAbs().maxCoeff(), kOffsetAbs_m)
          << "actuator " << a << " sample " << k;
    }
  }
  // The helix path's offset has the routing's radius; the straight one the offset's norm.
  EXPECT_NEAR((point(2, 3) - point(0, 3)).norm(), 0.002, kOffsetAbs_m);
  EXPECT_NEAR((point(1, 3) - point(0, 3)).norm(), std::hypot(0.003, 0.001), kOffsetAbs_m);
}

TEST(ShapeCurves, AStringAnchoredInsideTheBodyIsDrawnOverItsSpanOnly) {
  RodModel model = sample_model();
  model.actuators[0].span_m = std::array<double, 2>{0.01, 0.03};
  const Result result = sample_result(9);  // s = 0, 5, 10, ..., 40 mm
  const std::vector<ShapeCurve> curves = shape_curves(model, result);
  ASSERT_EQ(curves.size(), 3u);
  EXPECT_EQ(curves[1].s_m, std::vector<double>(result.centerline_s_m.begin() + 2,
                                               result.centerline_s_m.begin() + 7));
  ASSERT_EQ(curves[1].p_W_m.size(), 5u);
  EXPECT_EQ(curves[1].p_W_m[0],
            result.centerline_p_W_m[2] +
                result.centerline_R_WB[2] * model.actuators[0].routing.r(result.centerline_s_m[2]));
  EXPECT_EQ(curves[2].s_m.size(), 9u);  // no span: base to tip
}

TEST(Vtp, EmptyCenterlineGivesAValidEmptyPiece) {
  const std::string doc = vtp_document(sample_model(), Result{});
  EXPECT_TRUE(tags_balanced(doc));
  EXPECT_EQ(attribute(doc, "NumberOfPoints"), "0");
  EXPECT_EQ(attribute(doc, "NumberOfLines"), "0");
}

TEST(Vtp, InconsistentOrNonFiniteCenterlineIsRejected) {
  Result bad = sample_result(4);
  bad.centerline_R_WB.pop_back();
  EXPECT_THROW(vtp_document(sample_model(), bad), std::invalid_argument);
  Result nan = sample_result(4);
  nan.centerline_p_W_m[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(vtp_document(sample_model(), nan), DomainError);
}

TEST(Vtp, UnwritablePathThrowsInputErrorNamingTheFile) {
  try {
    write_vtp(sample_model(), sample_result(3), "/nonexistent-dir/x.vtp");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "vtk file");
    EXPECT_NE(e.value().find("/nonexistent-dir/x.vtp"), std::string::npos);
  }
}

TEST(ShapeCsv, OneRowPerPointWithCurveNamesAndNumbersThatReadBack) {
  const RodModel model = sample_model();
  const Result result = sample_result(3);
  std::istringstream in(shape_csv_document(model, result));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "curve,actuator_id,s_m,x_m,y_m,z_m");
  std::map<std::string, int> rows;
  std::vector<std::string> first_cells;
  int k = 0;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string curve, id, s, x, y, z;
    std::getline(cells, curve, ',');
    std::getline(cells, id, ',');
    std::getline(cells, s, ',');
    std::getline(cells, x, ',');
    std::getline(cells, y, ',');
    std::getline(cells, z, ',');
    ++rows[curve];
    if (curve == "centerline") {
      EXPECT_EQ(id, "-1");
      EXPECT_EQ(std::stod(s), result.centerline_s_m[k]);
      EXPECT_EQ(Eigen::Vector3d(std::stod(x), std::stod(y), std::stod(z)),
                result.centerline_p_W_m[k]);
      ++k;
    }
  }
  EXPECT_EQ(rows, (std::map<std::string, int>{{"centerline", 3}, {"tca-left", 3}, {"helix", 3}}));
}

}  // namespace
}  // namespace tcasim::rod

namespace tcasim::rod {
namespace {

TEST(ObstaclesVtp, OneSurfacePerObstacleWithItsPolygonCounts) {
  RodModel m = sample_model();
  EXPECT_EQ(obstacles_vtp_document(m, sample_result(5)), "");
  Obstacle floor;
  floor.name = "floor";
  floor.direction_W = Eigen::Vector3d::UnitZ();
  Obstacle ball;
  ball.name = "ball";
  ball.type = Obstacle::Type::kSphere;
  ball.point_W_m = {0.0, 0.1, 0.02};
  ball.radius_m = 0.01;
  Obstacle block;
  block.name = "block";
  block.type = Obstacle::Type::kBox;
  block.half_extents_m = {0.01, 0.02, 0.03};
  block.point_W_m = {0.2, 0, 0};
  m.obstacles = {floor, ball, block};
  const std::string doc = obstacles_vtp_document(m, sample_result(5));
  // Plane: one quad; sphere: 64 x 32 quads; box: six faces.
  EXPECT_NE(doc.find("NumberOfPolys=\"2055\""), std::string::npos);
  EXPECT_NE(doc.find("NumberOfPoints=\"2140\""), std::string::npos);  // 4 + 64 x 33 + 6 x 4
  EXPECT_NE(doc.find("Name=\"obstacle_names\" NumberOfTuples=\"3\""), std::string::npos);
  // The sphere's poles lie on its surface.
  EXPECT_NE(doc.find("0 0.10000000000000001 0.029999999999999999"), std::string::npos);
  EXPECT_EQ(obstacles_vtp_path("out/rod.vtp"), "out/rod.obstacles.vtp");
  EXPECT_EQ(obstacles_vtp_path("rod"), "rod.obstacles.vtp");
}

}  // namespace
}  // namespace tcasim::rod
