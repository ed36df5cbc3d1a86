#include "rod/result.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <iostream>

#include "common/error.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "rod/output_file.hpp"

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Lateral tip offset (relative to L) below which the rod counts as straight: far below
/// any deflection of interest, far above the round-off of a straight solve (~1e-16 L).
constexpr double kStraightLateralRelative = 1e-12;
/// Three points count as collinear when the sine of the angle at the base is below this.
constexpr double kCollinearSine = 1e-12;
/// A sample within this fraction of L of L/2 is used as the middle point directly.
constexpr double kSampleMatchRelative = 1e-12;
/// Largest field count listed in a non-finite message.
constexpr std::size_t kMaxListedFields = 6;
/// Discretization values up to this magnitude that are whole numbers are written as integers.
constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53

/// Builds JSON numbers and records every non-finite one (written as null instead).
class FiniteWriter {
 public:
  json number(double v, const std::string& field) {
    if (!std::isfinite(v)) {
      bad_.push_back(field);
      return nullptr;
    }
    return v;
  }
  json vector(const Eigen::Vector3d& v, const std::string& field) {
    json a = json::array();
    for (int i = 0; i < 3; ++i) a.push_back(number(v[i], fmt::format("{}[{}]", field, i)));
    return a;
  }
  /// A 3x3 matrix as three rows (row-major), as tip.rotation.
  json matrix(const Eigen::Matrix3d& m, const std::string& field) {
    json rows = json::array();
    for (int r = 0; r < 3; ++r) {
      json row = json::array();
      for (int c = 0; c < 3; ++c)
        row.push_back(number(m(r, c), fmt::format("{}[{}][{}]", field, r, c)));
      rows.push_back(row);
    }
    return rows;
  }
  const std::vector<std::string>& bad() const { return bad_; }

 private:
  std::vector<std::string> bad_;
};

/// Pose of the centerline at arc length s_m. Between two samples the strains are taken
/// constant, which makes the pose an SE(3) geodesic:
///   R(t) = R_a exp(t phi),  p(t) = p_a + R_a Jl(t phi) t rho,
/// with (phi, rho) = log of the relative pose, phi = log(R_a^T R_b),
/// rho = Jl(phi)^-1 R_a^T (p_b - p_a). Exact for arcs and helices (constant strains).
void pose_at(double s_m, double length_m, const std::vector<double>& s,
             const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Matrix3d>& R,
             Eigen::Vector3d& p_out, Eigen::Matrix3d& R_out) {
  const double match = kSampleMatchRelative * length_m;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (std::abs(s[i] - s_m) <= match) {
      p_out = p[i];
      R_out = R[i];
      return;
    }
  }
  auto hi = std::upper_bound(s.begin(), s.end(), s_m);
  if (hi == s.begin()) ++hi;
  if (hi == s.end()) --hi;
  const auto b = static_cast<std::size_t>(hi - s.begin());
  const std::size_t a = b - 1;
  const double t = (s_m - s[a]) / (s[b] - s[a]);
  const Eigen::Vector3d phi = so3::log(Eigen::Matrix3d(R[a].transpose() * R[b]));
  const Eigen::Vector3d rho = so3::left_jacobian_inverse(phi) * (R[a].transpose() * (p[b] - p[a]));
  R_out = R[a] * so3::exp(t * phi);
  p_out = p[a] + R[a] * (so3::left_jacobian(t * phi) * (t * rho));
}

}  // namespace

nlohmann::json to_json(const Result& result) {
  assert(result.centerline_s_m.size() == result.centerline_p_W_m.size());
  FiniteWriter w;
  json j;
  j["schema"] = "tcasim.result/1";
  j["scenario"] = result.scenario;
  j["method"] = result.method;

  json disc = json::object();
  for (const auto& [key, value] : result.discretization) {
    const std::string field = "discretization." + key;
    if (std::isfinite(value) && value == std::floor(value) && std::abs(value) <= kMaxExactInteger) {
      disc[key] = static_cast<long long>(value);
    } else {
      disc[key] = w.number(value, field);
    }
  }
  j["discretization"] = disc;
  j["iterations"] = result.iterations;
  j["residual"] = result.residual ? w.number(*result.residual, "residual") : json(nullptr);
  j["characteristic_force_N"] = w.number(result.characteristic_force_N, "characteristic_force_N");
  j["wall_time_s"] = w.number(result.wall_time_s, "wall_time_s");

  j["tip"] = {{"position_m", w.vector(result.tip_position_W_m, "tip.position_m")},
              {"rotation", w.matrix(result.tip_R_WB, "tip.rotation")}};

  json actuators = json::array();
  for (std::size_t i = 0; i < result.actuators.size(); ++i) {
    const ActuatorResult& a = result.actuators[i];
    const std::string field = fmt::format("actuators[{}]", i);
    json entry = {{"name", a.name},
                  {"tension_N", w.number(a.tension_N, field + ".tension_N")},
                  {"elongation_m", w.number(a.elongation_m, field + ".elongation_m")}};
    if (a.is_tca) {
      entry["coils_closed"] = a.coils_closed;
      entry["contact_force_N"] = w.number(a.contact_force_N, field + ".contact_force_N");
    }
    if (!a.segments.empty()) {
      json segs = json::array();
      for (std::size_t k = 0; k < a.segments.size(); ++k) {
        const auto& [seg, contact] = a.segments[k];
        const std::string sf = fmt::format("{}.segments[{}]", field, k);
        segs.push_back(
            {{"fraction", w.number(seg.fraction, sf + ".fraction")},
             {"temperature_degC",
              w.number(units::K_to_degC(seg.temperature_K), sf + ".temperature_degC")},
             {"coils_closed", contact.coils_closed},
             {"contact_force_N", w.number(contact.contact_force_N, sf + ".contact_force_N")}});
      }
      entry["segments"] = segs;
    }
    actuators.push_back(std::move(entry));
  }
  j["actuators"] = actuators;
  j["bending_radius_m"] = result.bending_radius_m
                              ? w.number(*result.bending_radius_m, "bending_radius_m")
                              : json(nullptr);
  if (result.tip_reaction_force_W_N) {
    j["tip_reaction_force_N"] = w.vector(*result.tip_reaction_force_W_N, "tip_reaction_force_N");
  }

  if (!result.probes.empty()) {
    json probes = json::array();
    for (std::size_t i = 0; i < result.probes.size(); ++i) {
      probes.push_back({{"name", result.probes[i].name},
                        {"position_m", w.vector(result.probes[i].position_W_m,
                                                fmt::format("probes[{}].position_m", i))}});
    }
    j["probes"] = probes;
  }

  if (!result.contacts.empty()) {
    json contacts = json::array();
    for (std::size_t i = 0; i < result.contacts.size(); ++i) {
      const ContactResult& c = result.contacts[i];
      const std::string field = fmt::format("contacts[{}]", i);
      json regions = json::array();
      for (std::size_t k = 0; k < c.regions.size(); ++k) {
        const std::string rf = fmt::format("{}.regions[{}]", field, k);
        regions.push_back({{"s_m",
                            {w.number(c.regions[k].s0_m, rf + ".s_m[0]"),
                             w.number(c.regions[k].s1_m, rf + ".s_m[1]")}},
                           {"force_N", w.vector(c.regions[k].force_W_N, rf + ".force_N")}});
      }
      contacts.push_back(
          {{"obstacle", c.obstacle},
           {"force_N", w.vector(c.force_W_N, field + ".force_N")},
           {"moment_Nm", w.vector(c.moment_W_Nm, field + ".moment_Nm")},
           {"regions", regions},
           {"max_penetration_m", w.number(c.max_penetration_m, field + ".max_penetration_m")},
           {"core_penetration_between_m",
            w.number(c.core_penetration_between_m, field + ".core_penetration_between_m")}});
    }
    j["contacts"] = contacts;
    // Static solves are frictionless (docs/scenario-format.md "Obstacles").
    j["contact_model"] = "frictionless";
  }
  if (result.base_reaction) {
    j["base_reaction"] = {
        {"force_N", w.vector(result.base_reaction->force_W_N, "base_reaction.force_N")},
        {"moment_Nm", w.vector(result.base_reaction->moment_W_Nm, "base_reaction.moment_Nm")}};
  }

  json s_m = json::array();
  json p_m = json::array();
  json R_m = json::array();
  // Rotations are written when every sample has one (a result built by hand may omit them).
  const bool rotations = result.centerline_R_WB.size() == result.centerline_s_m.size();
  for (std::size_t k = 0; k < result.centerline_s_m.size(); ++k) {
    s_m.push_back(w.number(result.centerline_s_m[k], fmt::format("centerline.s_m[{}]", k)));
    p_m.push_back(
        w.vector(result.centerline_p_W_m[k], fmt::format("centerline.position_m[{}]", k)));
    if (rotations) {
      R_m.push_back(w.matrix(result.centerline_R_WB[k], fmt::format("centerline.rotation[{}]", k)));
    }
  }
  j["centerline"] = {{"s_m", s_m}, {"position_m", p_m}};
  if (rotations) j["centerline"]["rotation"] = R_m;

  bool converged = result.converged;
  std::string message = result.message;
  if (!w.bad().empty()) {
    converged = false;
    const auto& bad = w.bad();
    std::vector<std::string> listed(bad.begin(), bad.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                                   bad.size(), kMaxListedFields)));
    std::string note = fmt::format(
        "non-finite value written as null in {}{}", fmt::join(listed, ", "),
        bad.size() > listed.size() ? fmt::format(" and {} more", bad.size() - listed.size())
                                   : std::string());
    message = message.empty() ? note : message + "; " + note;
  }
  j["converged"] = converged;
  // A converged solve whose result holds a non-finite number is not reported as converged.
  j["status"] =
      converged || result.status != "converged" ? result.status : std::string("non_finite_result");
  if (!converged) {
    j["message"] =
        message.empty() ? std::string("the solver did not converge (no reason given)") : message;
  }
  return j;
}

void set_coil_contacts(const Actuator& actuator, const std::vector<tca::Segment>& segments,
                       ActuatorResult& out) {
  const Drive& d = actuator.drive;
  if (d.type != Drive::Type::kTca || !d.tca) return;
  out.is_tca = true;
  const std::vector<tca::SegmentContact> c = tca::segment_contacts(*d.tca, out.tension_N, segments);
  out.coils_closed = false;
  out.contact_force_N = 0.0;
  for (const tca::SegmentContact& ck : c) {
    out.coils_closed = out.coils_closed || ck.coils_closed;
    out.contact_force_N = std::max(out.contact_force_N, ck.contact_force_N);
  }
  out.segments.clear();
  if (d.segmented) {
    for (std::size_t k = 0; k < segments.size(); ++k) out.segments.emplace_back(segments[k], c[k]);
  }
}

namespace {

bool is_scalar(const json& v) { return !v.is_structured(); }

void append_json(const json& j, int indent, std::string& out) {
  if (j.is_object() && !j.empty()) {
    out += "{\n";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (!first) out += ",\n";
      first = false;
      out.append(indent + 2, ' ');
      out += json(it.key()).dump();
      out += ": ";
      append_json(it.value(), indent + 2, out);
    }
    out += '\n';
    out.append(indent, ' ');
    out += '}';
  } else if (j.is_array() && !j.empty() && std::all_of(j.begin(), j.end(), is_scalar)) {
    out += '[';
    for (std::size_t k = 0; k < j.size(); ++k) {
      if (k > 0) out += ", ";
      out += j[k].dump();
    }
    out += ']';
  } else if (j.is_array() && !j.empty()) {
    out += "[\n";
    for (std::size_t k = 0; k < j.size(); ++k) {
      if (k > 0) out += ",\n";
      out.append(indent + 2, ' ');
      append_json(j[k], indent + 2, out);
    }
    out += '\n';
    out.append(indent, ' ');
    out += ']';
  } else {
    out += j.dump();  // a scalar, {} or []
  }
}

}  // namespace

std::string format_json(const json& j) {
  std::string out;
  append_json(j, 0, out);
  return out;
}

void write_result(const Result& result, const std::string& path) {
  const std::string text = format_json(to_json(result)) + "\n";
  if (path.empty() || path == "-") {
    std::cout << text << std::flush;
    if (!std::cout) throw InputError("result file", "\"-\"", "could not be written to stdout");
    return;
  }
  write_file_atomically(path, text, "result file");
}

std::optional<double> three_point_inner_radius(const RodModel& model,
                                               const std::vector<double>& s_m,
                                               const std::vector<Eigen::Vector3d>& p_W_m,
                                               const std::vector<Eigen::Matrix3d>& R_WB) {
  assert(s_m.size() == p_W_m.size() && s_m.size() == R_WB.size());
  assert(s_m.size() >= 2);
  if (s_m.size() < 2 || p_W_m.size() != s_m.size() || R_WB.size() != s_m.size())
    return std::nullopt;
  // A custom section has no outline, hence no inner edge (documented in the header).
  if (model.section.shape == Section::Shape::kCustom) return std::nullopt;

  const double length_m = s_m.back() - s_m.front();
  // Bending direction u_B: the chord from base to tip, expressed in the base body frame,
  // projected onto the section plane. For a planar arc of any turning angle in (0, 2 pi)
  // this points toward the centre of curvature, whatever the reference curvature, so
  // the points below lie on the concave (inner) side.
  const Eigen::Vector3d chord_B = R_WB.front().transpose() * (p_W_m.back() - p_W_m.front());
  const Eigen::Vector2d lateral = chord_B.head<2>();
  if (lateral.norm() <= kStraightLateralRelative * length_m) return std::nullopt;
  const Eigen::Vector2d u = lateral.normalized();
  const double h = model.section.half_extent_m(u.x(), u.y());
  const Eigen::Vector3d edge_B(h * u.x(), h * u.y(), 0.0);

  Eigen::Vector3d p_mid;
  Eigen::Matrix3d R_mid;
  pose_at(0.5 * (s_m.front() + s_m.back()), length_m, s_m, p_W_m, R_WB, p_mid, R_mid);

  const Eigen::Vector3d a = p_W_m.front() + R_WB.front() * edge_B;
  const Eigen::Vector3d b = p_mid + R_mid * edge_B;
  const Eigen::Vector3d c = p_W_m.back() + R_WB.back() * edge_B;
  const double ab = (b - a).norm();
  const double bc = (c - b).norm();
  const double ca = (a - c).norm();
  const double twice_area = (b - a).cross(c - a).norm();
  if (!(twice_area > kCollinearSine * ab * ca)) return std::nullopt;
  // Circumradius abc/(4 area).
  return ab * bc * ca / (2.0 * twice_area);
}

}  // namespace tcasim::rod
