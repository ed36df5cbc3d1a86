// Obstacle distances, the section gap and the contact results (rod/obstacle.hpp).
#include "rod/obstacle.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::rod {
namespace {

/// A unit vector normal to the unit vector a (for the undefined normal on an axis).
Eigen::Vector3d any_normal(const Eigen::Vector3d& a) {
  const Eigen::Vector3d t =
      std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (t - t.dot(a) * a).normalized();
}

Obstacle::Distance box_distance(const Obstacle& o, const Eigen::Vector3d& x) {
  const Eigen::Vector3d y = o.R_WO.transpose() * (x - o.point_W_m);
  const Eigen::Vector3d q = y.cwiseAbs() - o.half_extents_m;
  Obstacle::Distance d;
  if ((q.array() > 0.0).any()) {
    Eigen::Vector3d out = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) {
      if (q[i] > 0.0) out[i] = y[i] >= 0.0 ? q[i] : -q[i];
    }
    d.distance_m = out.norm();
    d.normal_W = o.R_WO * (out / d.distance_m);
    return d;
  }
  int i = 0;
  d.distance_m = q.maxCoeff(&i);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[i] = y[i] >= 0.0 ? 1.0 : -1.0;
  d.normal_W = o.R_WO * e;
  return d;
}

/// The point of the segment [a, b] nearest to the obstacle; returns the parameter t in [0, 1].
/// A sphere's or cylinder's signed distance grows with the distance from its center or axis,
/// whose square is a quadratic in t: its clamped minimum is exact. A box's is convex but only
/// piecewise smooth: golden-section search.
double nearest_on_segment(const Obstacle& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (o.type == Obstacle::Type::kSphere || o.type == Obstacle::Type::kCylinder) {
    Eigen::Vector3d e = b - a, v = a - o.point_W_m;
    if (o.type == Obstacle::Type::kCylinder) {  // the components across the axis
      e -= e.dot(o.direction_W) * o.direction_W;
      v -= v.dot(o.direction_W) * o.direction_W;
    }
    const double ee = e.squaredNorm();
    // An edge along the axis keeps its distance: any point, the middle.
    if (!(ee > 0.0)) return 0.5;
    return std::clamp(-v.dot(e) / ee, 0.0, 1.0);
  }
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0;
  double t1 = hi - g * (hi - lo), t2 = lo + g * (hi - lo);
  double f1 = o.distance(a + t1 * (b - a)).distance_m;
  double f2 = o.distance(a + t2 * (b - a)).distance_m;
  // 80 reductions by 0.618: an interval of 1e-17 of the edge, below round-off.
  for (int k = 0; k < 80 && hi - lo > 1e-15; ++k) {
    if (f1 <= f2) {
      hi = t2;
      t2 = t1;
      f2 = f1;
      t1 = hi - g * (hi - lo);
      f1 = o.distance(a + t1 * (b - a)).distance_m;
    } else {
      lo = t1;
      t1 = t2;
      f1 = f2;
      t2 = lo + g * (hi - lo);
      f2 = o.distance(a + t2 * (b - a)).distance_m;
    }
  }
  return 0.5 * (lo + hi);
}

SectionGap point_gap(const Obstacle& o, const Eigen::Vector3d& p, const Eigen::Vector3d& c) {
  const Obstacle::Distance d = o.distance(p + c);
  SectionGap g;
  g.gap_m = d.distance_m;
  g.normal_W = d.normal_W;
  g.offset_W_m = c;
  return g;
}

}  // namespace

Obstacle::Distance Obstacle::distance(const Eigen::Vector3d& x) const {
  Distance d;
  switch (type) {
    case Type::kPlane:
      d.distance_m = direction_W.dot(x - point_W_m);
      d.normal_W = direction_W;
      return d;
    case Type::kSphere: {
      const Eigen::Vector3d v = x - point_W_m;
      const double r = v.norm();
      d.distance_m = r - radius_m;
      d.normal_W = r > 0.0 ? Eigen::Vector3d(v / r) : Eigen::Vector3d::UnitZ();
      return d;
    }
    case Type::kCylinder: {
      const Eigen::Vector3d v = x - point_W_m;
      const Eigen::Vector3d radial = v - v.dot(direction_W) * direction_W;
      const double r = radial.norm();
      d.distance_m = r - radius_m;
      d.normal_W = r > 0.0 ? Eigen::Vector3d(radial / r) : any_normal(direction_W);
      return d;
    }
    case Type::kBox:
      return box_distance(*this, x);
  }
  return d;
}

const char* to_string(Obstacle::Type type) {
  switch (type) {
    case Obstacle::Type::kPlane:
      return "plane";
    case Obstacle::Type::kCylinder:
      return "cylinder";
    case Obstacle::Type::kSphere:
      return "sphere";
    case Obstacle::Type::kBox:
      return "box";
  }
  return "?";
}

ContactOutline contact_outline_at(const RodModel& model, double s_m, Side side) {
  ContactOutline out;
  switch (model.section.shape) {
    case Section::Shape::kCircle:
      out.kind = ContactOutline::Kind::kCircle;
      out.width_m = out.height_m = model.section.width_profile.value(s_m, side);
      break;
    case Section::Shape::kRectangle:
      out.kind = ContactOutline::Kind::kRectangle;
      out.width_m = model.section.width_profile.value(s_m, side);
      out.height_m = model.section.height_profile.value(s_m, side);
      break;
    case Section::Shape::kCustom:
      if (model.section.contact_radius_m) {
        out.kind = ContactOutline::Kind::kCircle;
        out.width_m = out.height_m = 2.0 * *model.section.contact_radius_m;
      }
      break;
  }
  return out;
}

int contact_candidate_count(ContactOutline::Kind kind) {
  return kind == ContactOutline::Kind::kRectangle ? 8 : 1;
}

std::vector<SectionGap> section_gaps(const Obstacle& obstacle, const ContactOutline& outline,
                                     const Eigen::Vector3d& p, const Eigen::Matrix3d& R_WB) {
  std::vector<SectionGap> out;
  if (outline.kind == ContactOutline::Kind::kRectangle) {
    out.reserve(8);
    const double a = 0.5 * outline.width_m, b = 0.5 * outline.height_m;
    const std::array<Eigen::Vector3d, 4> corners = {
        R_WB * Eigen::Vector3d(a, b, 0.0), R_WB * Eigen::Vector3d(-a, b, 0.0),
        R_WB * Eigen::Vector3d(-a, -b, 0.0), R_WB * Eigen::Vector3d(a, -b, 0.0)};
    for (const Eigen::Vector3d& c : corners) out.push_back(point_gap(obstacle, p, c));
    for (std::size_t j = 0; j < 4; ++j) {
      SectionGap edge;
      edge.gap_m = std::numeric_limits<double>::infinity();
      if (obstacle.type != Obstacle::Type::kPlane) {
        const Eigen::Vector3d& c0 = corners[j];
        const Eigen::Vector3d& c1 = corners[(j + 1) % 4];
        const double t = nearest_on_segment(obstacle, p + c0, p + c1);
        // Strictly inside: a minimum at a corner is that corner's candidate already.
        const SectionGap g = point_gap(obstacle, p, c0 + t * (c1 - c0));
        // A candidate of its own only where the edge bulges toward the obstacle: an interior
        // minimum below both corners' gaps by more than 1e-6 of the edge. Where the distance
        // is (nearly) constant along the edge (a face across a cylinder, on a box face) its
        // two corners hold the line contact, and a third, dependent, candidate would make
        // the solvers' systems singular.
        const double corners_gap = std::min(out[j].gap_m, out[(j + 1) % 4].gap_m);
        if (t > 1e-6 && t < 1.0 - 1e-6 && g.gap_m < corners_gap - 1e-6 * (c1 - c0).norm()) {
          edge = g;
        } else {
          edge.offset_W_m = t <= 0.5 ? c0 : c1;
        }
      }
      out.push_back(edge);
    }
    return out;
  }
  const Obstacle::Distance d = obstacle.distance(p);
  SectionGap g;
  g.normal_W = d.normal_W;
  g.gap_m = d.distance_m;
  if (outline.kind == ContactOutline::Kind::kCircle) {
    const double r = 0.5 * outline.width_m;
    const Eigen::Vector3d t = R_WB.col(2);
    // The outline point farthest along -n: -r times the unit projection of n on the section.
    const Eigen::Vector3d n_section = d.normal_W - d.normal_W.dot(t) * t;
    const double len = n_section.norm();
    g.offset_W_m =
        len > 0.0 ? Eigen::Vector3d(-r * n_section / len) : Eigen::Vector3d(r * R_WB.col(0));
    g.gap_m = d.distance_m - r * len;
  }
  out.push_back(g);
  return out;
}

SectionGap section_gap(const Obstacle& obstacle, const ContactOutline& outline,
                       const Eigen::Vector3d& p_W_m, const Eigen::Matrix3d& R_WB) {
  const std::vector<SectionGap> all = section_gaps(obstacle, outline, p_W_m, R_WB);
  return *std::min_element(all.begin(), all.end(), [](const SectionGap& x, const SectionGap& y) {
    return x.gap_m < y.gap_m;
  });
}

ContactResult summarize_contact(const Obstacle& obstacle, const std::vector<ContactSample>& samples,
                                const Eigen::Vector3d& base_W_m) {
  ContactResult r;
  r.obstacle = obstacle.name;
  bool previous_touching = false;  // the previous section (group of samples at one s) touched
  for (std::size_t k = 0; k < samples.size();) {
    // One section: the consecutive samples at the same s (a rectangle's candidates).
    std::size_t end = k;
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    bool touching = false;
    for (; end < samples.size() && samples[end].s_m == samples[k].s_m; ++end) {
      const ContactSample& c = samples[end];
      r.max_penetration_m = std::max(r.max_penetration_m, -c.gap_m);
      r.force_W_N += c.force_W_N;
      r.moment_W_Nm += (c.point_W_m - base_W_m).cross(c.force_W_N);
      force += c.force_W_N;
      touching = touching || c.force_W_N.squaredNorm() > 0.0;
    }
    if (touching && previous_touching) {
      r.regions.back().s1_m = samples[k].s_m;
      r.regions.back().force_W_N += force;
    } else if (touching) {
      r.regions.push_back({samples[k].s_m, samples[k].s_m, force});
    }
    previous_touching = touching;
    k = end;
  }
  return r;
}

namespace {

/// The stress-free pose at s: p' = R e3, R' = R hat(omega*(s)), from the clamp, by steps of
/// the exact exponential of omega* at each step's midpoint (exact for a constant omega*).
struct ReferenceWalker {
  const RodModel& model;
  double s = 0.0;
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  explicit ReferenceWalker(const RodModel& m) : model(m), p(m.base_position_W_m), R(m.R_WB0) {}
  void advance_to(double s1) {
    while (s < s1) {
      const double h = std::min(s1 - s, model.length_m / 20000.0);
      const Eigen::Vector3d w = model.reference_curvature_at(s + 0.5 * h);
      const double a = w.norm() * h;
      // Exact pose increment of a constant-strain piece (nu = e3, omega = w) over h.
      Eigen::Matrix3d dR = Eigen::Matrix3d::Identity();
      Eigen::Vector3d dp = h * Eigen::Vector3d::UnitZ();
      if (a > 0.0) {
        const Eigen::Vector3d k = w.normalized();
        dR = Eigen::AngleAxisd(a, k).toRotationMatrix();
        Eigen::Matrix3d K;
        K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
        const Eigen::Matrix3d V = Eigen::Matrix3d::Identity() * h +
                                  (1.0 - std::cos(a)) / w.norm() * K +
                                  (a - std::sin(a)) / w.norm() * K * K;
        dp = V * Eigen::Vector3d::UnitZ();
      }
      p += R * dp;
      R = R * dR;
      s += h;
    }
  }
};

}  // namespace

void check_between_contact_points(const RodModel& model, Result& result) {
  const auto& s = result.centerline_s_m;
  const auto& p = result.centerline_p_W_m;
  if (model.obstacles.empty() || result.contacts.size() != model.obstacles.size() || s.size() < 2 ||
      p.size() != s.size()) {
    return;
  }
  std::string worst;
  for (std::size_t o = 0; o < model.obstacles.size(); ++o) {
    const Obstacle& ob = model.obstacles[o];
    ContactResult& c = result.contacts[o];
    c.core_penetration_between_m = 0.0;
    c.core_penetration_s_m = 0.0;
    if (ob.type == Obstacle::Type::kPlane) continue;
    double worst_ratio = 0.0, worst_spacing = 0.0;
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
      const double t = nearest_on_segment(ob, p[k], p[k + 1]);
      if (!(t > 0.0 && t < 1.0)) continue;  // at a contact point: the solver's own gap
      const double s_t = s[k] + t * (s[k + 1] - s[k]);
      const ContactOutline out = contact_outline_at(model, s_t);
      if (out.kind == ContactOutline::Kind::kNone) continue;
      const double inradius = 0.5 * std::min(out.width_m, out.height_m);
      const double depth = inradius - ob.distance(p[k] + t * (p[k + 1] - p[k])).distance_m;
      if (depth > c.core_penetration_between_m) {
        c.core_penetration_between_m = depth;
        c.core_penetration_s_m = s_t;
      }
      if (depth > 0.5 * inradius && depth / inradius > worst_ratio) {
        worst_ratio = depth / inradius;
        worst_spacing = s[k + 1] - s[k];
      }
    }
    if (worst_ratio > 0.0 && worst.empty()) {
      // A spacing of half the obstacle's thickness keeps a contact point on it.
      double thickness = 2.0 * ob.radius_m;
      if (ob.type == Obstacle::Type::kBox) thickness = 2.0 * ob.half_extents_m.minCoeff();
      worst = fmt::format(
          "the rod passes into obstacles[{}] \"{}\" between its contact points near s = {:.6g} m: "
          "the core of its section (the inscribed circle) is {:.3g} m inside, more than half its "
          "inradius; the contact points are {:.3g} m apart there, refine the grid (shooting "
          "steps, FE elements) to a spacing below about {:.3g} m",
          o, ob.name, c.core_penetration_s_m, c.core_penetration_between_m, worst_spacing,
          0.5 * thickness);
    }
  }
  if (!worst.empty() && result.converged) {
    result.converged = false;
    result.status = "passes_between_contact_points";
    result.message = worst;
  }
}

void check_obstacles(const RodModel& model) {
  if (model.obstacles.empty()) return;
  const double L = model.length_m;
  if (model.section.shape == Section::Shape::kCustom && !model.section.contact_radius_m) {
    throw InputError("body.section.contact_radius_m", "(missing)",
                     "is required for a custom section when the scenario has obstacles (the "
                     "section has no outline to touch with)");
  }
  for (std::size_t i = 0; i < model.obstacles.size(); ++i) {
    const Obstacle& o = model.obstacles[i];
    const double d0 = o.distance(model.base_position_W_m).distance_m;
    require(d0 > 0.0, fmt::format("obstacles[{}]", i), fmt::format("\"{}\"", o.name),
            fmt::format("must not contain the base point (base.position_m): its distance from "
                        "the surface is {} m",
                        format_value(d0)));
  }
  // Every 1/1000 of L, every breakpoint, both ends.
  std::vector<double> s_list;
  for (int k = 0; k <= 1000; ++k) s_list.push_back(L * k / 1000.0);
  for (double b : model.breakpoints()) s_list.push_back(b);
  std::sort(s_list.begin(), s_list.end());
  // Round-off of the reference pose (and of a shape meant to touch at rest): 1e-9 L.
  const double tolerance = 1e-9 * L;
  ReferenceWalker walk(model);
  for (double s : s_list) {
    walk.advance_to(s);
    for (const Side side : {Side::kLeft, Side::kRight}) {
      const ContactOutline outline = contact_outline_at(model, s, side);
      for (std::size_t i = 0; i < model.obstacles.size(); ++i) {
        const SectionGap g = section_gap(model.obstacles[i], outline, walk.p, walk.R);
        require(g.gap_m >= -tolerance, fmt::format("obstacles[{}]", i),
                fmt::format("\"{}\"", model.obstacles[i].name),
                fmt::format("must not be penetrated by the reference (stress-free) shape: the "
                            "section at s = {} m lies {} m inside it",
                            format_value(s), format_value(-g.gap_m)));
      }
    }
  }
}

}  // namespace tcasim::rod
