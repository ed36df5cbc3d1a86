#include "rod/vtk.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "common/error.hpp"
#include "rod/output_file.hpp"

namespace tcasim::rod {
namespace {

/// A VTK String array in ASCII: each string as its byte codes, terminated by 0.
std::string string_array(const std::string& name, const std::vector<std::string>& values) {
  std::string text;
  for (const auto& v : values) {
    for (unsigned char c : v) text += fmt::format("{} ", static_cast<int>(c));
    text += "0 ";
  }
  if (!text.empty()) text.pop_back();
  return fmt::format(
      "      <DataArray type=\"String\" Name=\"{}\" NumberOfTuples=\"{}\" format=\"ascii\">\n"
      "        {}\n"
      "      </DataArray>\n",
      name, values.size(), text);
}

/// CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::vector<ShapeCurve> shape_curves(const RodModel& model, const Result& result) {
  const std::size_t n = result.centerline_s_m.size();
  if (result.centerline_p_W_m.size() != n || result.centerline_R_WB.size() != n) {
    throw std::invalid_argument(
        fmt::format("shape_curves: centerline arrays differ in length (s: {}, p: {}, R: {})", n,
                    result.centerline_p_W_m.size(), result.centerline_R_WB.size()));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(result.centerline_s_m[k]) || !result.centerline_p_W_m[k].allFinite() ||
        !result.centerline_R_WB[k].allFinite()) {
      throw DomainError(fmt::format("shape of '{}': centerline sample {} (of {}) is not finite",
                                    result.scenario, k, n));
    }
  }
  std::vector<ShapeCurve> curves;
  curves.push_back({"centerline", -1, result.centerline_s_m, result.centerline_p_W_m});
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const Actuator& a = model.actuators[i];
    ShapeCurve c{a.name, static_cast<int>(i), {}, {}};
    c.p_W_m.reserve(n);
    // A string anchored inside the body is drawn over its span only (both solvers sample
    // the anchors: they are knots).
    const double lo = a.span_start_m(), hi = a.span_end_m(model.length_m);
    for (std::size_t k = 0; k < n; ++k) {
      const double s = result.centerline_s_m[k];
      // (a round-off margin: a sample at an anchor may be a sum like s0 + h)
      const double tol = 1e-12 * model.length_m;
      if (a.span_m && (s < lo - tol || s > hi + tol)) continue;
      // String path in the world frame: q_i = p + R r_i(s) (r_i in the body frame).
      c.s_m.push_back(s);
      c.p_W_m.push_back(result.centerline_p_W_m[k] + result.centerline_R_WB[k] * a.routing.r(s));
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

std::string vtp_document(const RodModel& model, const Result& result) {
  const std::vector<ShapeCurve> curves = shape_curves(model, result);
  // Curves with fewer than 2 points are not lines; keep the point data consistent by
  // writing only the curves that are.
  std::size_t points = 0, lines = 0;
  for (const auto& c : curves) {
    if (c.p_W_m.size() >= 2) {
      points += c.p_W_m.size();
      ++lines;
    }
  }
  std::string coords, s_values, ids, connectivity, offsets, cell_ids;
  std::vector<std::string> names;
  std::size_t next = 0;
  for (const auto& c : curves) {
    if (c.p_W_m.size() < 2) continue;
    names.push_back(c.name);
    for (std::size_t k = 0; k < c.p_W_m.size(); ++k) {
      const Eigen::Vector3d& p = c.p_W_m[k];
      // 17 significant digits: every number reads back to the same double.
      coords += fmt::format("          {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
      s_values += fmt::format("{:.17g} ", c.s_m[k]);
      ids += fmt::format("{} ", c.actuator_id);
      connectivity += fmt::format("{} ", next++);
    }
    offsets += fmt::format("{} ", next);
    cell_ids += fmt::format("{} ", c.actuator_id);
  }

  std::string doc;
  doc += "<?xml version=\"1.0\"?>\n";
  doc +=
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  doc += "  <PolyData>\n";
  doc += "    <FieldData>\n";
  doc += string_array("scenario", {result.scenario});
  doc += string_array("method", {result.method});
  doc += string_array("curve_names", names);
  doc += "    </FieldData>\n";
  doc += fmt::format(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
      "NumberOfStrips=\"0\" "
      "NumberOfPolys=\"0\">\n",
      points, lines);
  doc += "      <PointData Scalars=\"s_m\">\n";
  doc += "        <DataArray type=\"Float64\" Name=\"s_m\" format=\"ascii\">\n          " +
         s_values + "\n";
  doc += "        </DataArray>\n";
  doc += "        <DataArray type=\"Int32\" Name=\"actuator_id\" format=\"ascii\">\n          " +
         ids + "\n";
  doc += "        </DataArray>\n";
  doc += "      </PointData>\n";
  doc += "      <CellData Scalars=\"actuator_id\">\n";
  doc += "        <DataArray type=\"Int32\" Name=\"actuator_id\" format=\"ascii\">\n          " +
         cell_ids + "\n";
  doc += "        </DataArray>\n";
  doc += "      </CellData>\n";
  doc += "      <Points>\n";
  doc +=
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n" +
      coords;
  doc += "        </DataArray>\n";
  doc += "      </Points>\n";
  doc += "      <Lines>\n";
  doc += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n          " +
         connectivity + "\n";
  doc += "        </DataArray>\n";
  doc += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n          " +
         offsets + "\n";
  doc += "        </DataArray>\n";
  doc += "      </Lines>\n";
  doc += "    </Piece>\n";
  doc += "  </PolyData>\n";
  doc += "</VTKFile>\n";
  return doc;
}

void write_vtp(const RodModel& model, const Result& result, const std::string& path) {
  write_file_atomically(path, vtp_document(model, result), "vtk file");
  if (!model.obstacles.empty()) {
    write_file_atomically(obstacles_vtp_path(path), obstacles_vtp_document(model, result),
                          "vtk file");
  }
}

std::string obstacles_vtp_path(const std::string& path) {
  const std::string ending = ".vtp";
  if (path.size() >= ending.size() &&
      path.compare(path.size() - ending.size(), ending.size(), ending) == 0) {
    return path.substr(0, path.size() - ending.size()) + ".obstacles.vtp";
  }
  return path + ".obstacles.vtp";
}

namespace {

/// Polygons of one surface: points and, per polygon, its point indices.
struct Surface {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::size_t>> polygons;
};

/// Two unit vectors spanning the plane normal to the unit vector a.
void tangent_basis(const Eigen::Vector3d& a, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d t =
      std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = (t - t.dot(a) * a).normalized();
  v = a.cross(u);
}

/// A grid of quads over the parameter rectangle [0, 1]^2 of `at` (nu x nv cells).
template <class F>
void add_grid(Surface& out, int nu, int nv, bool wrap_u, const F& at) {
  const std::size_t first = out.points.size();
  const int cols = wrap_u ? nu : nu + 1;
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i < cols; ++i) {
      out.points.push_back(at(static_cast<double>(i) / nu, static_cast<double>(j) / nv));
    }
  }
  const auto index = [&](int i, int j) {
    return first + static_cast<std::size_t>(j * cols + (wrap_u ? i % nu : i));
  };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      out.polygons.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
}

Surface obstacle_surface(const Obstacle& o, const Eigen::Vector3d& centre, double half_size) {
  Surface s;
  constexpr double kPi = 3.14159265358979323846;
  switch (o.type) {
    case Obstacle::Type::kPlane: {
      Eigen::Vector3d u, v;
      tangent_basis(o.direction_W, u, v);
      const Eigen::Vector3d c = centre - o.direction_W.dot(centre - o.point_W_m) * o.direction_W;
      add_grid(s, 1, 1, false, [&](double a, double b) {
        return Eigen::Vector3d(c + half_size * ((2 * a - 1) * u + (2 * b - 1) * v));
      });
      break;
    }
    case Obstacle::Type::kCylinder: {
      Eigen::Vector3d u, v;
      tangent_basis(o.direction_W, u, v);
      const Eigen::Vector3d c =
          o.point_W_m + o.direction_W.dot(centre - o.point_W_m) * o.direction_W;
      add_grid(s, 64, 1, true, [&](double a, double b) {
        const double phi = 2 * kPi * a;
        return Eigen::Vector3d(c + o.radius_m * (std::cos(phi) * u + std::sin(phi) * v) +
                               half_size * (2 * b - 1) * o.direction_W);
      });
      break;
    }
    case Obstacle::Type::kSphere:
      add_grid(s, 64, 32, true, [&](double a, double b) {
        const double phi = 2 * kPi * a, theta = kPi * b;
        return Eigen::Vector3d(o.point_W_m +
                               o.radius_m * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                            std::sin(theta) * std::sin(phi),
                                                            std::cos(theta)));
      });
      break;
    case Obstacle::Type::kBox: {
      // Six faces, each a quad of the box's corners (outward order is not needed for display).
      for (int axis = 0; axis < 3; ++axis) {
        for (const double side : {-1.0, 1.0}) {
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          add_grid(s, 1, 1, false, [&](double a, double b) {
            Eigen::Vector3d y;
            y[axis] = side * o.half_extents_m[axis];
            y[a1] = (2 * a - 1) * o.half_extents_m[a1];
            y[a2] = (2 * b - 1) * o.half_extents_m[a2];
            return Eigen::Vector3d(o.point_W_m + o.R_WO * y);
          });
        }
      }
      break;
    }
  }
  return s;
}

}  // namespace

std::string obstacles_vtp_document(const RodModel& model, const Result& result) {
  if (model.obstacles.empty()) return {};
  // The patch of the unbounded shapes: around the centerline's bounding box.
  Eigen::Vector3d lo = model.base_position_W_m, hi = model.base_position_W_m;
  for (const Eigen::Vector3d& p : result.centerline_p_W_m) {
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double half_size = 0.5 * (hi - lo).norm() + 0.5 * model.length_m;
  std::string coords, connectivity, offsets, ids;
  std::vector<std::string> names;
  std::size_t points = 0, polygons = 0, next = 0;
  for (std::size_t i = 0; i < model.obstacles.size(); ++i) {
    const Surface surface = obstacle_surface(model.obstacles[i], centre, half_size);
    names.push_back(model.obstacles[i].name);
    for (const Eigen::Vector3d& p : surface.points) {
      coords += fmt::format("          {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
    }
    for (const auto& poly : surface.polygons) {
      for (std::size_t k : poly) connectivity += fmt::format("{} ", points + k);
      next += poly.size();
      offsets += fmt::format("{} ", next);
      ids += fmt::format("{} ", i);
    }
    points += surface.points.size();
    polygons += surface.polygons.size();
  }
  std::string doc;
  doc += "<?xml version=\"1.0\"?>\n";
  doc +=
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  doc += "  <PolyData>\n";
  doc += "    <FieldData>\n";
  doc += string_array("scenario", {result.scenario});
  doc += string_array("obstacle_names", names);
  doc += "    </FieldData>\n";
  doc += fmt::format(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
      points, polygons);
  doc += "      <CellData Scalars=\"obstacle_id\">\n";
  doc += "        <DataArray type=\"Int32\" Name=\"obstacle_id\" format=\"ascii\">\n          " +
         ids + "\n";
  doc += "        </DataArray>\n";
  doc += "      </CellData>\n";
  doc += "      <Points>\n";
  doc +=
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n" +
      coords;
  doc += "        </DataArray>\n";
  doc += "      </Points>\n";
  doc += "      <Polys>\n";
  doc += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n          " +
         connectivity + "\n";
  doc += "        </DataArray>\n";
  doc += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n          " +
         offsets + "\n";
  doc += "        </DataArray>\n";
  doc += "      </Polys>\n";
  doc += "    </Piece>\n";
  doc += "  </PolyData>\n";
  doc += "</VTKFile>\n";
  return doc;
}

std::string shape_csv_document(const RodModel& model, const Result& result) {
  std::string text = "curve,actuator_id,s_m,x_m,y_m,z_m\n";
  for (const auto& c : shape_curves(model, result)) {
    const std::string name = csv_field(c.name);
    for (std::size_t k = 0; k < c.p_W_m.size(); ++k) {
      const Eigen::Vector3d& p = c.p_W_m[k];
      text += fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g}\n", name, c.actuator_id, c.s_m[k],
                          p.x(), p.y(), p.z());
    }
  }
  return text;
}

void write_shape_csv(const RodModel& model, const Result& result, const std::string& path) {
  write_file_atomically(path, shape_csv_document(model, result), "shape csv file");
}

}  // namespace tcasim::rod
