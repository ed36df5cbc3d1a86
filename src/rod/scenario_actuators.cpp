// Scenario reader: actuators (routing, drives, rest lengths).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/internal/scenario_reading.hpp"
#include "rod/reference_path.hpp"
#include "rod/scenario.hpp"

namespace tcasim::rod::scenario_detail {
namespace {

// ---------------------------------------------------------------------------------------
// Actuators

/// Largest distance from the centerline an offset may have in direction (x, y); none
/// for a custom section (no outline to check against).
std::optional<double> edge_distance(const Section& s, double x, double y) {
  if (s.shape == Section::Shape::kCustom) return std::nullopt;
  return s.half_extent_m(x, y) * (1.0 + kEdgeRelativeTolerance);
}

/// The section against which offsets are checked: for a section that varies along s, the
/// smallest listed width and height (a piecewise linear profile is smallest at a listed
/// point; for a rectangle whose two sides are smallest at different s this is conservative).
Section narrowest_section(const Section& s) {
  if (!s.varies()) return s;
  Section n = s;
  n.width_profile = Profile(s.width_profile.min_value());
  n.height_profile = Profile(s.height_profile.min_value());
  return n;
}

/// The section's outline at s (at a jump: the narrower of the two sides), for the offset
/// check of a routing whose offset varies along s.
Section outline_at(const Section& s, double s_m) {
  if (!s.varies()) return s;
  Section n = s;
  const SectionProperties l = s.properties_at(s_m, Side::kLeft);
  const SectionProperties r = s.properties_at(s_m, Side::kRight);
  n.width_profile = Profile(std::min(l.width_m, r.width_m));
  n.height_profile = Profile(std::min(l.height_m, r.height_m));
  return n;
}

/// Samples per cubic piece at which the spline is checked against the section edge.
constexpr int kSplineEdgeSamples = 32;

/// `type: "spline"` (docs/scenario-format.md "General routing and string extent"): knots
/// strictly increasing inside [0, L], one offset per knot, every knot (and, for a cubic,
/// samples between them; for a linear one, the section's breakpoints between them) inside
/// the section at its own s.
Routing parse_spline(const json& j, const std::string& path, const Section& section,
                     double length_m) {
  const Obj o(j, path, {"type", "s_m", "offset_m", "interpolation"});
  Routing r;
  r.type = Routing::Type::kSpline;
  r.linear = o.has("interpolation") && o.choice("interpolation", {"cubic", "linear"}) == "linear";
  const json& s = o.required("s_m");
  if (!s.is_array() || s.size() < 2) {
    throw InputError(o.key("s_m"), show(s), "must be an array of at least two numbers (knots)");
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::string ki = fmt::format("{}[{}]", o.key("s_m"), i);
    r.knot_s_m.push_back(as_number(s[i], ki));
    require(
        r.knot_s_m.back() >= 0.0 && r.knot_s_m.back() <= length_m, ki, r.knot_s_m.back(),
        fmt::format("must lie inside the body [0, {}] m (body.length_m)", format_value(length_m)));
    require(i == 0 || r.knot_s_m[i] > r.knot_s_m[i - 1], ki, r.knot_s_m.back(),
            fmt::format("must be greater than s_m[{}] = {} (knots strictly increasing)", i - 1,
                        i > 0 ? format_value(r.knot_s_m[i - 1]) : std::string()));
  }
  const json& p = o.required("offset_m");
  if (!p.is_array() || p.size() != s.size()) {
    throw InputError(
        o.key("offset_m"), show(p),
        fmt::format("must be an array of {} points [x, y], one per entry of s_m", s.size()));
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::string ki = fmt::format("{}[{}]", o.key("offset_m"), i);
    if (!p[i].is_array() || p[i].size() != 2) {
      throw InputError(ki, show(p[i]), "must be an array of 2 numbers [x, y]");
    }
    r.knot_offsets_m.emplace_back(as_number(p[i][0], ki + "[0]"), as_number(p[i][1], ki + "[1]"));
  }
  r.build_spline();
  if (section.shape == Section::Shape::kCustom) return r;
  // The knots first (named by index), then, for a cubic, points between them.
  const auto check = [&](double sk, const std::string& where, const std::string& shown) {
    const Eigen::Vector3d x = r.r(sk, Side::kLeft);
    const double dist = x.head<2>().norm();
    if (!(dist > 0.0)) return;
    const Section local = outline_at(section, sk);
    require(dist <= *edge_distance(local, x.x(), x.y()), where, shown,
            fmt::format("puts the string outside the body section at s = {} m: {} m from the "
                        "centerline, the edge is at {} m in that direction",
                        format_value(sk), dist, local.half_extent_m(x.x(), x.y())));
  };
  for (std::size_t i = 0; i < r.knot_s_m.size(); ++i) {
    check(r.knot_s_m[i], fmt::format("{}[{}]", o.key("offset_m"), i), show(p[i]));
  }
  if (r.linear) {
    // A straight piece inside a convex section whose size is linear in s between two checked
    // points stays inside (distance convex, edge linear): the section's breakpoints in between
    // are checked too.
    for (const Profile* pr : {&section.width_profile, &section.height_profile}) {
      for (const double sb : pr->breakpoints()) {
        if (sb > r.knot_s_m.front() && sb < r.knot_s_m.back()) {
          check(sb, o.key("offset_m"), show(p));
        }
      }
    }
    return r;
  }
  for (std::size_t i = 0; i + 1 < r.knot_s_m.size(); ++i) {
    for (int k = 1; k < kSplineEdgeSamples; ++k) {
      check(r.knot_s_m[i] + (r.knot_s_m[i + 1] - r.knot_s_m[i]) * k / kSplineEdgeSamples,
            o.key("offset_m"), show(p));
    }
  }
  return r;
}

Routing parse_routing(const json& j, const std::string& path, const Section& body_section,
                      double length_m) {
  const std::string type = peek_choice(j, path, "type", {"straight", "helix", "spline"});
  if (type == "spline") return parse_spline(j, path, body_section, length_m);
  // A constant offset (or radius) must fit the narrowest section along the body.
  const Section section = narrowest_section(body_section);
  Routing r;
  if (type == "straight") {
    const Obj o(j, path, {"type", "offset_m"});
    r.type = Routing::Type::kStraight;
    r.offset_m = o.vector2("offset_m");
    const double dist = r.offset_m.norm();
    if (dist > 0.0) {
      if (const auto limit = edge_distance(section, r.offset_m.x(), r.offset_m.y())) {
        require(dist <= *limit, o.key("offset_m"), show(o.required("offset_m")),
                fmt::format("lies outside the body section: {} m from the centerline, the edge "
                            "is at {} m in that direction",
                            dist, section.half_extent_m(r.offset_m.x(), r.offset_m.y())));
      }
    }
  } else {
    const Obj o(j, path, {"type", "radius_m", "phase_deg", "turns_per_m"});
    r.type = Routing::Type::kHelix;
    r.radius_m = o.positive("radius_m");
    r.phase_rad = units::deg_to_rad(o.optional_number("phase_deg").value_or(0.0));
    r.turns_per_m = o.number("turns_per_m");
    if (section.shape != Section::Shape::kCustom) {
      // The helix sweeps every direction: it must fit where the section is narrowest.
      const double narrowest =
          std::min(section.half_extent_m(1.0, 0.0), section.half_extent_m(0.0, 1.0));
      require(r.radius_m <= narrowest * (1.0 + kEdgeRelativeTolerance), o.key("radius_m"),
              r.radius_m,
              fmt::format("puts the helix outside the body section (narrowest half extent {} m)",
                          narrowest));
    }
  }
  return r;
}

/// A drive temperature [degC] checked against absolute zero and the TCA material's range.
double check_drive_temperature_K(double t_degC, const std::string& key, const tca::Tca& t) {
  const double t_K = above_absolute_zero_K(t_degC, key);
  const tca::Material& m = t.material();
  require(t_K >= m.min_temperature_K && t_K <= m.max_temperature_K, key, t_degC,
          fmt::format("is outside the valid range [{:.10g}, {:.10g}] degC of material '{}'",
                      units::K_to_degC(m.min_temperature_K), units::K_to_degC(m.max_temperature_K),
                      m.name));
  try {
    (void)m.at(t_K);
  } catch (const DomainError& e) {
    throw InputError(key, format_value(t_degC),
                     fmt::format("is outside the domain of material '{}': {}", m.name, e.what()));
  }
  return t_K;
}

/// A drive temperature [degC], a number or a time profile, as a profile in kelvin; its lowest
/// and highest values are checked as check_drive_temperature_K.
TimeProfile parse_drive_temperature_K(const Obj& o, const std::string& k, const tca::Tca& t) {
  const std::string key = o.key(k);
  const TimeProfile p_degC = parse_time_profile(o.required(k), key);
  (void)check_drive_temperature_K(p_degC.min_value(), key, t);
  (void)check_drive_temperature_K(p_degC.max_value(), key, t);
  return p_degC.affine(units::kZeroCelsius_K, 1.0);
}

/// An electric segment of a segmented TCA drive (every segment electric, or none): adds it
/// to d and returns true; returns false for a temperature segment.
bool parse_segment_electric(const Obj& so, std::size_t i, Drive& d, double f,
                            const RodModel& model) {
  const bool el = so.has("electric");
  if (i > 0 && el != d.is_electric()) {
    throw InputError(so.key(el ? "electric" : "temperature_degC"), "(given)",
                     "must be of the same kind in every segment (all temperature_degC or all "
                     "electric)");
  }
  if (!el) return false;
  require(!so.has("temperature_degC"), so.key("temperature_degC"), "(given)",
          "must not be given together with electric (give exactly one)");
  double t0_K = 0.0;
  d.electric.push_back(
      parse_electric(so.required("electric"), so.key("electric"), d.tca_id, f, model, t0_K));
  d.segments.push_back(tca::Segment{f, t0_K});
  return true;
}

Drive parse_drive(const json& j, const std::string& path, const RodModel& model) {
  const std::string type = peek_choice(j, path, "type", {"tension", "tca"});
  Drive d;
  if (type == "tension") {
    const Obj o(j, path, {"type", "tension_N"});
    d.type = Drive::Type::kTension;
    d.tension_profile_N = parse_time_profile(o.required("tension_N"), o.key("tension_N"));
    d.tension_N = d.tension_profile_N.value(0.0);
    return d;
  }
  const Obj o(j, path, {"type", "tca", "temperature_degC", "segments", "electric"});
  d.type = Drive::Type::kTca;
  d.tca_id = o.string("tca");
  const auto it = model.tcas.find(d.tca_id);
  if (it == model.tcas.end()) {
    std::vector<std::string> ids;
    for (const auto& kv : model.tcas) ids.push_back(kv.first);
    throw InputError(
        o.key("tca"), quote(d.tca_id),
        fmt::format("is not a key of tcas (defined: {})",
                    ids.empty() ? std::string("none") : fmt::format("{}", fmt::join(ids, ", "))));
  }
  d.tca = it->second;
  const bool has_t = o.has("temperature_degC");
  const bool has_seg = o.has("segments");
  const bool has_el = o.has("electric");
  if (has_t + has_seg + has_el > 1) {
    throw InputError(o.key(has_el ? "electric" : "segments"),
                     show(o.required(has_el ? "electric" : "segments")),
                     "must not be given together with temperature_degC, segments or electric "
                     "(give exactly one)");
  }
  if (!has_t && !has_seg && !has_el) {
    throw InputError(o.key("temperature_degC"), "(missing)",
                     "is required unless segments or electric is given (give exactly one)");
  }
  if (has_t) {
    d.temperature_profiles_K = {parse_drive_temperature_K(o, "temperature_degC", *d.tca)};
    d.segments = {tca::Segment{1.0, d.temperature_profiles_K[0].value(0.0)}};
    return d;
  }
  if (has_el) {
    double t0_K = 0.0;
    d.electric = {
        parse_electric(o.required("electric"), o.key("electric"), d.tca_id, 1.0, model, t0_K)};
    d.segments = {tca::Segment{1.0, t0_K}};
    return d;
  }
  d.segmented = true;
  const json& segs = o.required("segments");
  if (!segs.is_array() || segs.empty()) {
    throw InputError(o.key("segments"), show(segs),
                     "must be a non-empty array of {\"fraction\", \"temperature_degC\"}");
  }
  if (segs.size() > kMaxSegments) {
    throw InputError(o.key("segments"), fmt::format("(an array of {} segments)", segs.size()),
                     fmt::format("must have at most {} segments", kMaxSegments));
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Obj so(segs[i], fmt::format("{}[{}]", o.key("segments"), i),
                 {"fraction", "temperature_degC", "electric"});
    const double f = so.number("fraction");
    require(f > 0.0 && f <= 1.0, so.key("fraction"), f, "must lie in (0, 1]");
    sum += f;
    if (parse_segment_electric(so, i, d, f, model)) continue;
    d.temperature_profiles_K.push_back(parse_drive_temperature_K(so, "temperature_degC", *d.tca));
    d.segments.push_back(tca::Segment{f, d.temperature_profiles_K.back().value(0.0)});
  }
  require(std::abs(sum - 1.0) <= kFractionSumTolerance, o.key("segments"),
          fmt::format("(fractions summing to {})", format_value(sum)),
          fmt::format("must have fractions summing to 1 (within {})", kFractionSumTolerance));
  return d;
}

/// `span_m: [s_start, s_end]` (docs/scenario-format.md "String extent"): two numbers with
/// 0 <= s_start < s_end <= L.
std::array<double, 2> parse_span(const Obj& o, double length_m) {
  const Eigen::Vector2d v = o.vector2("span_m");
  const std::string shown = show(o.required("span_m"));
  require(
      v[0] >= 0.0 && v[1] <= length_m, o.key("span_m"), shown,
      fmt::format("must lie inside the body [0, {}] m (body.length_m)", format_value(length_m)));
  require(v[1] > v[0], o.key("span_m"), shown,
          "must be increasing: s_start < s_end (the string's anchors, base side first)");
  return {v[0], v[1]};
}

/// The rest length of one string of `a` (docs/scenario-format.md, "Rest length and
/// regularity"): the reference path length, less the TCA's pre-elongation for a TCA drive.
/// Refuses a reference path that folds, a coiled length that does not match the path
/// without a pre_elongation_m, and a pre-elongation the TCA cannot have.
double rest_length(const Obj& o, const Actuator& a, const RodModel& model) {
  const ReferencePath ref =
      reference_path(a.routing, model, a.span_start_m(), a.span_end_m(model.length_m));
  const bool helix = a.routing.type == Routing::Type::kHelix;
  const std::string routing_key = o.key(helix ? "routing.radius_m" : "routing.offset_m");
  require(
      ref.min_axial > 0.0, routing_key,
      helix ? format_value(a.routing.radius_m) : show(o.required("routing").at("offset_m")),
      fmt::format("makes the reference string path fold on the precurved body: e3 . (e3 + "
                  "omega* x r + r') = {} at s = {} m, must be > 0 (for a straight string: the "
                  "offset toward the centre of curvature times |omega*_perp| must be < 1)",
                  fmt::format("{:.6g}", ref.min_axial), fmt::format("{:.6g}", ref.min_axial_s_m)));
  const bool has_pre = o.has("pre_elongation_m");
  if (a.drive.type != Drive::Type::kTca) {
    if (has_pre) {
      throw InputError(
          o.key("pre_elongation_m"), show(o.required("pre_elongation_m")),
          "applies only to a TCA drive (a tension drive's rest length is its path length)");
    }
    return ref.length_m;
  }
  const tca::Parameters& p = a.drive.tca->parameters();
  const std::string coiled_key = fmt::format("tcas.{}.coiled_length_m", a.drive.tca_id);
  if (!has_pre) {
    const double mismatch = (p.coiled_length_m - ref.length_m) / ref.length_m;
    require(std::abs(mismatch) <= kCoiledLengthRelativeTolerance, coiled_key, p.coiled_length_m,
            fmt::format("must equal the reference path length {} m of {} (within {} relative; it "
                        "differs by {:.3g}), or {} must give the TCA's elongation there",
                        fmt::format("{:.10g}", ref.length_m), o.path(),
                        kCoiledLengthRelativeTolerance, mismatch, o.key("pre_elongation_m")));
    return ref.length_m;
  }
  const double pre = a.pre_elongation_m;
  const std::string pre_key = o.key("pre_elongation_m");
  if (p.kind == tca::Kind::kExtension && !p.fiber_diameter_m) {
    require(pre >= 0.0, pre_key, pre,
            "must be >= 0 for an extension TCA (its coils cannot be shorter than closed)");
  } else if (a.drive.tca->has_coil_contact()) {
    const double dc = a.drive.tca->closed_elongation_m();
    require(pre >= dc, pre_key, pre,
            fmt::format("must be >= n d0 - L = {} m of TCA '{}' (its coils cannot be shorter than "
                        "closed: closed length n d0 = {} m)",
                        format_value(dc), a.drive.tca_id, format_value(p.coiled_length_m + dc)));
  }
  // delta = l (sin alpha - sin alpha0) with alpha in (0, 90) deg: -L < delta < l - L.
  require(
      pre > -p.coiled_length_m && pre < p.fiber_length_m - p.coiled_length_m, pre_key, pre,
      fmt::format("must lie in (-coiled_length_m, fiber_length_m - coiled_length_m) = ({}, {}) m "
                  "of TCA '{}' (a coil between flat and straight)",
                  format_value(-p.coiled_length_m),
                  format_value(p.fiber_length_m - p.coiled_length_m), a.drive.tca_id));
  require(
      pre < ref.length_m, pre_key, pre,
      fmt::format("must be below the reference path length {} m (the rest length must be positive)",
                  fmt::format("{:.10g}", ref.length_m)));
  return ref.length_m - pre;
}

}  // namespace

Actuator parse_actuator(const json& j, const std::string& path, const RodModel& model) {
  const Obj o(j, path,
              {"name", "comment", "routing", "count", "drive", "pre_elongation_m", "span_m"});
  Actuator a;
  a.name = o.nonempty_string("name");
  a.routing = parse_routing(o.required("routing"), o.key("routing"), model.section, model.length_m);
  if (o.has("count")) {
    // Parsed non-negative integers are unsigned in nlohmann::json (too large for long long
    // possibly); 1e9 or 2.0 are floats, which are refused.
    const json& c = o.required("count");
    const bool small = c.is_number_unsigned() ? c.get<unsigned long long>() <=
                                                    static_cast<unsigned long long>(kMaxCount)
                                              : c.is_number_integer();
    const long long n = small ? c.get<long long>() : 0;
    if (n < 1 || n > kMaxCount) {
      throw InputError(o.key("count"), show(c),
                       fmt::format("must be an integer in [1, {}]", kMaxCount));
    }
    a.count = static_cast<int>(n);
  }
  if (o.has("span_m")) a.span_m = parse_span(o, model.length_m);
  if (a.routing.type == Routing::Type::kSpline) {
    // docs/scenario-format.md "General routing and string extent": the span defaults to the
    // spline's knots and must lie inside them.
    const double lo = a.routing.knot_s_m.front(), hi = a.routing.knot_s_m.back();
    if (!a.span_m) {
      if (lo > 0.0 || hi < model.length_m) a.span_m = std::array<double, 2>{lo, hi};
    } else {
      require((*a.span_m)[0] >= lo && (*a.span_m)[1] <= hi, o.key("span_m"),
              show(o.required("span_m")),
              fmt::format("must lie inside the spline routing's knots [{}, {}] m (routing.s_m)",
                          format_value(lo), format_value(hi)));
    }
  }
  a.drive = parse_drive(o.required("drive"), o.key("drive"), model);
  if (a.drive.type == Drive::Type::kTca && o.has("pre_elongation_m")) {
    a.pre_elongation_m = o.number("pre_elongation_m");
  }
  a.rest_length_m = rest_length(o, a, model);
  return a;
}

}  // namespace tcasim::rod::scenario_detail
