// The `obstacles` list of a scenario (docs/scenario-format.md "Obstacles").
#include "rod/internal/scenario_reading.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

/// Obstacles of one scenario: each adds contact candidates at every contact point of both
/// solvers and four CSV columns; far more than any test rig holds.
constexpr std::size_t kMaxObstacles = 100;

/// A non-zero direction, normalized (key names the vector).
Eigen::Vector3d unit_vector(const Obj& o, const std::string& k) {
  const Eigen::Vector3d v = o.vector3(k);
  require(v.norm() > 0.0, o.key(k), show(o.required(k)), "must be non-zero");
  return v.normalized();
}

}  // namespace

std::vector<Obstacle> parse_obstacles(const json& j, const std::string& path) {
  if (!j.is_array()) {
    throw InputError(path, show(j),
                     fmt::format("must be an array of obstacle objects, not {}", type_name(j)));
  }
  if (j.size() > kMaxObstacles) {
    throw InputError(path, fmt::format("(an array of {} obstacles)", j.size()),
                     fmt::format("must have at most {} obstacles", kMaxObstacles));
  }
  std::vector<Obstacle> obstacles;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string p = fmt::format("{}[{}]", path, i);
    const std::string type = peek_choice(j[i], p, "type", {"plane", "cylinder", "sphere", "box"});
    std::vector<std::string> allowed{"name", "type", "friction"};
    if (type == "plane") allowed.insert(allowed.end(), {"point_m", "normal"});
    if (type == "cylinder") allowed.insert(allowed.end(), {"point_m", "axis", "radius_m"});
    if (type == "sphere") allowed.insert(allowed.end(), {"center_m", "radius_m"});
    if (type == "box") allowed.insert(allowed.end(), {"center_m", "half_extents_m", "rotation"});
    const Obj o(j[i], p, allowed);
    Obstacle ob;
    ob.name = o.nonempty_string("name");
    require(csv_safe(ob.name), o.key("name"), quote(ob.name),
            "must consist of letters, digits, '_', '-' and '.' only (it names CSV columns)");
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      require(obstacles[k].name != ob.name, o.key("name"), quote(ob.name),
              fmt::format("is not unique (also {}[{}].name)", path, k));
    }
    if (o.has("friction")) {
      ob.friction = o.number("friction");
      require(ob.friction >= 0.0, o.key("friction"), ob.friction, "must be >= 0");
    }
    if (type == "plane") {
      ob.type = Obstacle::Type::kPlane;
      ob.point_W_m = o.vector3("point_m");
      ob.direction_W = unit_vector(o, "normal");
    } else if (type == "cylinder") {
      ob.type = Obstacle::Type::kCylinder;
      ob.point_W_m = o.vector3("point_m");
      ob.direction_W = unit_vector(o, "axis");
      ob.radius_m = o.positive("radius_m");
    } else if (type == "sphere") {
      ob.type = Obstacle::Type::kSphere;
      ob.point_W_m = o.vector3("center_m");
      ob.direction_W = Eigen::Vector3d::Zero();
      ob.radius_m = o.positive("radius_m");
    } else {
      ob.type = Obstacle::Type::kBox;
      ob.point_W_m = o.vector3("center_m");
      ob.direction_W = Eigen::Vector3d::Zero();
      ob.half_extents_m = o.vector3("half_extents_m");
      for (int c = 0; c < 3; ++c) {
        require(ob.half_extents_m[c] > 0.0, fmt::format("{}[{}]", o.key("half_extents_m"), c),
                ob.half_extents_m[c], "must be positive");
      }
      if (o.has("rotation")) ob.R_WO = parse_rotation(o, "rotation");
    }
    obstacles.push_back(std::move(ob));
  }
  return obstacles;
}

}  // namespace tcasim::rod::scenario_detail
