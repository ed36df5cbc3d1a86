#include "rod/scenario.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "rod/json_file.hpp"
#include "rod/reference_path.hpp"

#ifndef TCASIM_DATA_DIR
#error "TCASIM_DATA_DIR must be defined by the build (src/rod/CMakeLists.txt)"
#endif

namespace tcasim::rod {
namespace {

using json = nlohmann::json;

/// Segment fractions are typed as decimals; their sum must be 1 up to this (far above
/// round-off of a few terms, far below any intended fraction).
constexpr double kFractionSumTolerance = 1e-9;
/// base.rotation: max |R^T R - I| and |det R - 1| allowed (10 typed digits per entry).
constexpr double kRotationTolerance = 1e-9;
/// An offset exactly on the section edge counts as inside; this relative slack absorbs
/// the round-off of the half-extent computation.
constexpr double kEdgeRelativeTolerance = 1e-12;
/// Longest value text quoted in a message.
constexpr std::size_t kMaxValueChars = 80;
/// Number of temperatures at which a material law is checked over its valid range.
constexpr int kMaterialRangeSamples = 201;
/// A TCA's coiled length must equal its string's reference path length within this
/// relative amount unless the actuator gives pre_elongation_m (docs/scenario-format.md):
/// far above the round-off of the path length, below any intended pre-elongation (1 um on 1 m).
constexpr double kCoiledLengthRelativeTolerance = 1e-6;
/// Upper bounds on counts, each with its reason. Parallel strings of one actuator: a
/// U-shaped TCA is 2 and each string needs its own channel in the section, so more than
/// 1000 cannot be a string actuator.
constexpr int kMaxCount = 1000;
/// Actuators of one rod: the shooting Newton system is dense in the TCA tensions (6 + n
/// unknowns) and every right-hand side loops over all strings; the paper's robots have
/// 1 to 4, and 256 keeps one solve within seconds.
constexpr std::size_t kMaxActuators = 256;
/// Segments of one TCA drive: every tension evaluation solves the series of all segments;
/// 1000 resolves any temperature profile far below the TCA's own length scale.
constexpr std::size_t kMaxSegments = 1000;

const std::string kScenarioSchema = "tcasim.scenario/1";
const std::string kTcasSchema = "tcasim.tcas/1";

std::string join_path(const std::string& prefix, const std::string& key) {
  if (prefix.empty()) return key;
  if (prefix.back() == ':') return prefix + key;
  return prefix + "." + key;
}

std::string show(const json& j) {
  std::string s = j.dump();
  if (s.size() > kMaxValueChars) s = s.substr(0, kMaxValueChars - 3) + "...";
  return s;
}

std::string quote(const std::string& s) { return json(s).dump(); }

/// Human-readable name of a JSON value's type, for "must be a number, not a string".
std::string type_name(const json& j) { return j.type_name(); }

double as_number(const json& v, const std::string& key) {
  if (!v.is_number()) {
    throw InputError(key, show(v), fmt::format("must be a number, not {}", type_name(v)));
  }
  const double x = v.get<double>();
  require(std::isfinite(x), key, x, "must be a finite number");
  return x;
}

/// A JSON object read strictly: every key must be in `allowed`, and every access names
/// its full key path in errors.
class Obj {
 public:
  Obj(const json& j, std::string path, std::vector<std::string> allowed)
      : j_(j), path_(std::move(path)) {
    if (!j.is_object()) {
      throw InputError(path_.empty() ? "(document)" : path_, show(j),
                       fmt::format("must be a JSON object, not {}", type_name(j)));
    }
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
        throw InputError(key(it.key()), show(it.value()),
                         fmt::format("is not an allowed key here (allowed: {})",
                                     fmt::join(allowed, ", ")));
      }
    }
  }

  std::string key(const std::string& k) const { return join_path(path_, k); }
  const std::string& path() const { return path_; }
  bool has(const std::string& k) const { return j_.contains(k); }

  const json& required(const std::string& k) const {
    if (!has(k)) throw InputError(key(k), "(missing)", "is required");
    return j_.at(k);
  }

  double number(const std::string& k) const { return as_number(required(k), key(k)); }

  std::optional<double> optional_number(const std::string& k) const {
    if (!has(k)) return std::nullopt;
    return number(k);
  }

  double positive(const std::string& k) const {
    const double x = number(k);
    require(x > 0.0, key(k), x, "must be positive");
    return x;
  }

  std::string string(const std::string& k) const {
    const json& v = required(k);
    if (!v.is_string()) {
      throw InputError(key(k), show(v), fmt::format("must be a string, not {}", type_name(v)));
    }
    return v.get<std::string>();
  }

  std::string nonempty_string(const std::string& k) const {
    std::string s = string(k);
    require(!s.empty(), key(k), quote(s), "must not be empty");
    return s;
  }

  std::string optional_string(const std::string& k) const { return has(k) ? string(k) : ""; }

  /// A string that must be one of `options`.
  std::string choice(const std::string& k, const std::vector<std::string>& options) const {
    std::string s = string(k);
    if (std::find(options.begin(), options.end(), s) == options.end()) {
      throw InputError(key(k), quote(s),
                       fmt::format("must be one of: {}", fmt::join(options, ", ")));
    }
    return s;
  }

  /// A fixed-size array of finite numbers.
  Eigen::VectorXd vector(const std::string& k, int size) const {
    const json& v = required(k);
    if (!v.is_array() || static_cast<int>(v.size()) != size) {
      throw InputError(key(k), show(v), fmt::format("must be an array of {} numbers", size));
    }
    Eigen::VectorXd out(size);
    for (int i = 0; i < size; ++i) {
      out[i] = as_number(v[static_cast<std::size_t>(i)], fmt::format("{}[{}]", key(k), i));
    }
    return out;
  }
  Eigen::Vector3d vector3(const std::string& k) const { return vector(k, 3); }
  Eigen::Vector2d vector2(const std::string& k) const { return vector(k, 2); }

 private:
  const json& j_;
  std::string path_;
};

/// Reads the discriminating string of a polymorphic object (e.g. `shape`, `type`) before
/// the object's allowed keys are known.
std::string peek_choice(const json& j, const std::string& path, const std::string& k,
                        const std::vector<std::string>& options) {
  if (!j.is_object()) {
    throw InputError(path.empty() ? "(document)" : path, show(j),
                     fmt::format("must be a JSON object, not {}", type_name(j)));
  }
  if (!j.contains(k)) {
    throw InputError(join_path(path, k), "(missing)",
                     fmt::format("is required (one of: {})", fmt::join(options, ", ")));
  }
  const json& v = j.at(k);
  const std::string key = join_path(path, k);
  if (!v.is_string()) {
    throw InputError(key, show(v), fmt::format("must be a string, not {}", type_name(v)));
  }
  const std::string s = v.get<std::string>();
  if (std::find(options.begin(), options.end(), s) == options.end()) {
    throw InputError(key, quote(s), fmt::format("must be one of: {}", fmt::join(options, ", ")));
  }
  return s;
}

// ---------------------------------------------------------------------------------------
// Body

/// Saint-Venant torsion constant of a w x h rectangle.
/// [TimoshenkoGoodier1970] Sec. 109 (torsion of a rectangular bar), with a >= b the sides:
///   J = a b^3/3 - (64 b^4/pi^5) sum_{n = 1, 3, 5, ...} tanh(n pi a/(2 b))/n^5.
/// The series is evaluated as sum 1/n^5 - sum (1 - tanh)/n^5: the first sum over odd n is
/// (1 - 2^-5) zeta(5) in closed form and the second decays like exp(-n pi), so the result
/// is exact to round-off after a handful of terms.
double rectangle_saint_venant_torsion(double w_m, double h_m) {
  constexpr double kZeta5 = 1.0369277551433699263;  // Riemann zeta(5)
  constexpr double kOddZeta5 = (31.0 / 32.0) * kZeta5;  // sum over odd n of 1/n^5
  constexpr int kMaxTerms = 200;
  const double a = std::max(w_m, h_m);
  const double b = std::min(w_m, h_m);
  double deficit = 0.0;  // sum (1 - tanh(x_n))/n^5
  for (int k = 0; k < kMaxTerms; ++k) {
    const double n = 2.0 * k + 1.0;
    const double x = n * units::kPi * a / (2.0 * b);
    const double e = std::exp(-2.0 * x);
    const double term = 2.0 * e / (1.0 + e) / std::pow(n, 5);  // 1 - tanh(x) = 2 e^-2x/(1 + e^-2x)
    deficit += term;
    if (term < std::numeric_limits<double>::epsilon() * 1e-3) break;
  }
  const double pi5 = std::pow(units::kPi, 5);
  return a * b * b * b / 3.0 - 64.0 * std::pow(b, 4) / pi5 * (kOddZeta5 - deficit);
}

Section parse_section(const json& j, const std::string& path) {
  const std::string shape = peek_choice(j, path, "shape", {"circle", "rectangle", "custom"});
  Section s;
  bool torsion_allowed = true;
  std::vector<std::string> allowed{"shape", "torsion"};
  if (shape == "circle") {
    allowed.push_back("diameter_m");
  } else if (shape == "rectangle") {
    allowed.insert(allowed.end(), {"width_m", "height_m"});
  } else {
    allowed = {"shape", "area_m2", "I_x_m4", "I_y_m4", "J_m4"};
    torsion_allowed = false;
  }
  const Obj o(j, path, allowed);
  if (torsion_allowed && o.has("torsion")) {
    s.saint_venant_torsion = o.choice("torsion", {"polar", "saint-venant"}) == "saint-venant";
  }
  if (shape == "circle") {
    s.shape = Section::Shape::kCircle;
    const double d = o.positive("diameter_m");
    s.width_m = d;
    s.height_m = d;
    s.area_m2 = units::kPi * d * d / 4.0;
    s.I_x_m4 = units::kPi * std::pow(d, 4) / 64.0;
    s.I_y_m4 = s.I_x_m4;
    // For a circle the Saint-Venant constant equals the polar moment.
    s.J_m4 = s.I_x_m4 + s.I_y_m4;
  } else if (shape == "rectangle") {
    s.shape = Section::Shape::kRectangle;
    const double w = o.positive("width_m");
    const double h = o.positive("height_m");
    s.width_m = w;
    s.height_m = h;
    s.area_m2 = w * h;
    s.I_x_m4 = w * h * h * h / 12.0;  // int y^2 dA, y along height
    s.I_y_m4 = h * w * w * w / 12.0;  // int x^2 dA, x along width
    s.J_m4 = s.saint_venant_torsion ? rectangle_saint_venant_torsion(w, h) : s.I_x_m4 + s.I_y_m4;
  } else {
    s.shape = Section::Shape::kCustom;
    s.area_m2 = o.positive("area_m2");
    s.I_x_m4 = o.positive("I_x_m4");
    s.I_y_m4 = o.positive("I_y_m4");
    s.J_m4 = o.positive("J_m4");
  }
  return s;
}

BodyMaterial parse_body_material(const Obj& o) {
  BodyMaterial m;
  m.youngs_modulus_Pa = o.positive("youngs_modulus_Pa");
  m.poisson_ratio = o.number("poisson_ratio");
  // 0.5 (incompressible) is allowed: the paper uses it for EcoFlex.
  require(m.poisson_ratio >= 0.0 && m.poisson_ratio <= 0.5, o.key("poisson_ratio"),
          m.poisson_ratio, "must lie in [0, 0.5]");
  m.shear_modulus_Pa = m.youngs_modulus_Pa / (2.0 * (1.0 + m.poisson_ratio));
  if (const auto psi = o.optional_number("density_kg_m3")) {
    require(*psi >= 0.0, o.key("density_kg_m3"), *psi, "must not be negative");
    m.density_kg_m3 = *psi;
  }
  return m;
}

Eigen::Matrix3d parse_rotation(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  const std::string key = o.key(k);
  const std::string shape_rule = "must be a 3x3 array of numbers (row-major)";
  if (!v.is_array() || v.size() != 3) throw InputError(key, show(v), shape_rule);
  Eigen::Matrix3d R;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_array() || v[i].size() != 3) throw InputError(key, show(v), shape_rule);
    for (std::size_t c = 0; c < 3; ++c) {
      R(static_cast<int>(i), static_cast<int>(c)) =
          as_number(v[i][c], fmt::format("{}[{}][{}]", key, i, c));
    }
  }
  const double orth = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  require(orth <= kRotationTolerance, key, show(v),
          fmt::format("must be orthonormal: max |R^T R - I| = {} > {}", orth, kRotationTolerance));
  const double det = R.determinant();
  require(std::abs(det - 1.0) <= kRotationTolerance, key, show(v),
          fmt::format("must have determinant +1 (a rotation, not a reflection): det = {}", det));
  // Project onto SO(3) (nearest rotation, polar decomposition) so that the typed
  // round-off does not propagate.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

// ---------------------------------------------------------------------------------------
// TCAs

tca::PolynomialDegC parse_property(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  tca::PolynomialDegC p;
  if (v.is_number()) {
    p.coefficients = {as_number(v, o.key(k))};
    return p;
  }
  if (!v.is_object()) {
    throw InputError(o.key(k), show(v),
                     "must be a number or {\"polynomial_degC\": [c0, c1, ...]}");
  }
  const Obj po(v, o.key(k), {"polynomial_degC"});
  const json& c = po.required("polynomial_degC");
  if (!c.is_array() || c.empty()) {
    throw InputError(po.key("polynomial_degC"), show(c),
                     "must be a non-empty array of coefficients [c0, c1, ...]");
  }
  for (std::size_t i = 0; i < c.size(); ++i) {
    p.coefficients.push_back(as_number(c[i], fmt::format("{}[{}]", po.key("polynomial_degC"), i)));
  }
  return p;
}

tca::F12Form parse_f12_form(const Obj& o) {
  return o.choice("f12_form", {"paper", "castigliano"}) == "paper" ? tca::F12Form::kPaper
                                                                   : tca::F12Form::kCastigliano;
}

/// Requires a temperature in degC to lie above absolute zero; returns it in kelvin.
double above_absolute_zero_K(double t_degC, const std::string& key) {
  require(t_degC > -units::kZeroCelsius_K, key, t_degC,
          t_degC < -units::kZeroCelsius_K ? "is below absolute zero"
                                          : "is not above absolute zero");
  return units::degC_to_K(t_degC);
}

/// Checks that E, G and the diameter ratio are positive at `t_K` (a material law that
/// is not cannot be evaluated there).
void check_material_positive_at(const tca::Material& m, double t_K, const std::string& key) {
  const double t_degC = units::K_to_degC(t_K);
  const double E = m.youngs_modulus_Pa.value(t_K);
  const double G = m.shear_modulus_Pa.value(t_K);
  require(E > 0.0, join_path(key, "youngs_modulus_Pa"), E,
          fmt::format("must be positive (value at {:.10g} degC)", t_degC));
  require(G > 0.0, join_path(key, "shear_modulus_Pa"), G,
          fmt::format("must be positive (value at {:.10g} degC)", t_degC));
  if (m.diameter.type == tca::DiameterLaw::Type::kLinearExpansion) {
    const double ratio = 1.0 + m.diameter.linear_expansion_1_K * (t_K - m.reference_temperature_K);
    require(ratio > 0.0, join_path(key, "diameter.linear_expansion_1_K"),
            m.diameter.linear_expansion_1_K,
            fmt::format("gives a non-positive diameter ratio {} at {:.10g} degC", ratio, t_degC));
  } else {
    const double ratio = m.diameter.ratio_polynomial.value(t_K) /
                         m.diameter.ratio_polynomial.value(m.reference_temperature_K);
    require(ratio > 0.0, join_path(key, "diameter.ratio_polynomial_degC"), ratio,
            fmt::format("is the diameter ratio at {:.10g} degC; it must be positive", t_degC));
  }
}

std::shared_ptr<const tca::Tca> parse_tca(const json& j, const std::string& path,
                                          const std::string& base_dir) {
  (void)base_dir;
  const Obj o(j, path,
              {"kind", "coiled_length_m", "fiber_length_m", "pitch_angle_deg", "outer_diameter_m",
               "twist_turns", "f12_form", "material", "comment"});
  tca::Parameters p;
  p.kind = o.choice("kind", {"extension", "contraction"}) == "extension" ? tca::Kind::kExtension
                                                                         : tca::Kind::kContraction;
  p.coiled_length_m = o.positive("coiled_length_m");
  const bool has_l = o.has("fiber_length_m");
  const bool has_alpha = o.has("pitch_angle_deg");
  if (has_l && has_alpha) {
    throw InputError(o.key("pitch_angle_deg"), show(o.required("pitch_angle_deg")),
                     "must not be given together with fiber_length_m (give exactly one)");
  }
  if (!has_l && !has_alpha) {
    throw InputError(o.key("fiber_length_m"), "(missing)",
                     "is required unless pitch_angle_deg is given (give exactly one)");
  }
  if (has_l) {
    p.fiber_length_m = o.positive("fiber_length_m");
  } else {
    const double alpha_deg = o.number("pitch_angle_deg");
    require(alpha_deg > 0.0 && alpha_deg < 90.0, o.key("pitch_angle_deg"), alpha_deg,
            "must lie in (0, 90)");
    p.fiber_length_m = tca::fiber_length_from_pitch(p.coiled_length_m, units::deg_to_rad(alpha_deg));
  }
  p.outer_diameter_m = o.positive("outer_diameter_m");
  p.twist_turns = o.positive("twist_turns");

  const json& mj = o.required("material");
  tca::Material material;
  if (mj.is_string()) {
    material = load_material(mj.get<std::string>(), o.key("material"));
  } else if (mj.is_object()) {
    material = parse_material(mj, o.key("material"));
  } else {
    throw InputError(o.key("material"), show(mj),
                     "must be a shipped material name (string) or an inline material object");
  }
  // Default f12 form: the material's, if its source states one, else the consistent
  // Castigliano factor (docs/conventions.md).
  p.f12_form = o.has("f12_form") ? parse_f12_form(o)
                                 : material.f12_form.value_or(tca::F12Form::kCastigliano);
  try {
    return std::make_shared<const tca::Tca>(p, std::move(material));
  } catch (const InputError& e) {
    throw InputError(join_path(path, e.key()), e.value(), e.rule());
  }
}

std::map<std::string, std::shared_ptr<const tca::Tca>> parse_tcas(const json& j,
                                                                  const std::string& path,
                                                                  const std::string& base_dir) {
  if (!j.is_object()) {
    throw InputError(path, show(j),
                     fmt::format("must be a JSON object of named TCAs, not {}", type_name(j)));
  }
  std::map<std::string, std::shared_ptr<const tca::Tca>> out;
  for (auto it = j.begin(); it != j.end(); ++it) {
    require(!it.key().empty(), path, quote(it.key()), "must not contain an empty TCA id");
    out.emplace(it.key(), parse_tca(it.value(), join_path(path, it.key()), base_dir));
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// Actuators

/// Largest distance from the centerline an offset may have in direction (x, y); none
/// for a custom section (no outline to check against).
std::optional<double> edge_distance(const Section& s, double x, double y) {
  if (s.shape == Section::Shape::kCustom) return std::nullopt;
  return s.half_extent_m(x, y) * (1.0 + kEdgeRelativeTolerance);
}

Routing parse_routing(const json& j, const std::string& path, const Section& section) {
  const std::string type = peek_choice(j, path, "type", {"straight", "helix"});
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
      const double narrowest = std::min(section.half_extent_m(1.0, 0.0), section.half_extent_m(0.0, 1.0));
      require(r.radius_m <= narrowest * (1.0 + kEdgeRelativeTolerance), o.key("radius_m"),
              r.radius_m,
              fmt::format("puts the helix outside the body section (narrowest half extent {} m)",
                          narrowest));
    }
  }
  return r;
}

/// A drive temperature [degC] checked against absolute zero and the TCA material's range.
double parse_drive_temperature_K(const Obj& o, const std::string& k, const tca::Tca& t) {
  const double t_degC = o.number(k);
  const std::string key = o.key(k);
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

Drive parse_drive(const json& j, const std::string& path, const RodModel& model) {
  const std::string type = peek_choice(j, path, "type", {"tension", "tca"});
  Drive d;
  if (type == "tension") {
    const Obj o(j, path, {"type", "tension_N"});
    d.type = Drive::Type::kTension;
    d.tension_N = o.number("tension_N");
    return d;
  }
  const Obj o(j, path, {"type", "tca", "temperature_degC", "segments"});
  d.type = Drive::Type::kTca;
  d.tca_id = o.string("tca");
  const auto it = model.tcas.find(d.tca_id);
  if (it == model.tcas.end()) {
    std::vector<std::string> ids;
    for (const auto& kv : model.tcas) ids.push_back(kv.first);
    throw InputError(o.key("tca"), quote(d.tca_id),
                     fmt::format("is not a key of tcas (defined: {})",
                                 ids.empty() ? std::string("none") : fmt::format("{}", fmt::join(ids, ", "))));
  }
  d.tca = it->second;
  const bool has_t = o.has("temperature_degC");
  const bool has_seg = o.has("segments");
  if (has_t && has_seg) {
    throw InputError(o.key("segments"), show(o.required("segments")),
                     "must not be given together with temperature_degC (give exactly one)");
  }
  if (!has_t && !has_seg) {
    throw InputError(o.key("temperature_degC"), "(missing)",
                     "is required unless segments is given (give exactly one)");
  }
  if (has_t) {
    d.segments = {tca::Segment{1.0, parse_drive_temperature_K(o, "temperature_degC", *d.tca)}};
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
    const Obj so(segs[i], fmt::format("{}[{}]", o.key("segments"), i), {"fraction", "temperature_degC"});
    const double f = so.number("fraction");
    require(f > 0.0 && f <= 1.0, so.key("fraction"), f, "must lie in (0, 1]");
    sum += f;
    d.segments.push_back(tca::Segment{f, parse_drive_temperature_K(so, "temperature_degC", *d.tca)});
  }
  require(std::abs(sum - 1.0) <= kFractionSumTolerance, o.key("segments"),
          fmt::format("(fractions summing to {})", format_value(sum)),
          fmt::format("must have fractions summing to 1 (within {})", kFractionSumTolerance));
  return d;
}

/// The rest length of one string of `a` (docs/scenario-format.md, "Rest length and
/// regularity"): the reference path length, less the TCA's pre-elongation for a TCA drive.
/// Refuses a reference path that folds, a coiled length that does not match the path
/// without a pre_elongation_m, and a pre-elongation the TCA cannot have.
double rest_length(const Obj& o, const Actuator& a, const RodModel& model) {
  const ReferencePath ref = reference_path(a.routing, model.reference_curvature_B_1_m, model.length_m);
  const bool straight = a.routing.type == Routing::Type::kStraight;
  const std::string routing_key = o.key(straight ? "routing.offset_m" : "routing.radius_m");
  require(ref.min_axial > 0.0, routing_key,
          straight ? show(o.required("routing").at("offset_m")) : format_value(a.routing.radius_m),
          fmt::format("makes the reference string path fold on the precurved body: e3 . (e3 + "
                      "omega* x r + r') = {} at s = {} m, must be > 0 (for a straight string: the "
                      "offset toward the centre of curvature times |omega*_perp| must be < 1)",
                      fmt::format("{:.6g}", ref.min_axial), fmt::format("{:.6g}", ref.min_axial_s_m)));
  const bool has_pre = o.has("pre_elongation_m");
  if (a.drive.type != Drive::Type::kTca) {
    if (has_pre) {
      throw InputError(o.key("pre_elongation_m"), show(o.required("pre_elongation_m")),
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
                        fmt::format("{:.10g}", ref.length_m), o.path(), kCoiledLengthRelativeTolerance, mismatch,
                        o.key("pre_elongation_m")));
    return ref.length_m;
  }
  const double pre = a.pre_elongation_m;
  const std::string pre_key = o.key("pre_elongation_m");
  if (p.kind == tca::Kind::kExtension) {
    require(pre >= 0.0, pre_key, pre,
            "must be >= 0 for an extension TCA (its coils cannot be shorter than closed)");
  }
  // delta = l (sin alpha - sin alpha0) with alpha in (0, 90) deg: -L < delta < l - L.
  require(pre > -p.coiled_length_m && pre < p.fiber_length_m - p.coiled_length_m, pre_key, pre,
          fmt::format("must lie in (-coiled_length_m, fiber_length_m - coiled_length_m) = ({}, {}) m "
                      "of TCA '{}' (a coil between flat and straight)",
                      format_value(-p.coiled_length_m), format_value(p.fiber_length_m - p.coiled_length_m),
                      a.drive.tca_id));
  require(pre < ref.length_m, pre_key, pre,
          fmt::format("must be below the reference path length {} m (the rest length must be positive)",
                      fmt::format("{:.10g}", ref.length_m)));
  return ref.length_m - pre;
}

Actuator parse_actuator(const json& j, const std::string& path, const RodModel& model) {
  const Obj o(j, path, {"name", "comment", "routing", "count", "drive", "pre_elongation_m"});
  Actuator a;
  a.name = o.nonempty_string("name");
  a.routing = parse_routing(o.required("routing"), o.key("routing"), model.section);
  if (o.has("count")) {
    // Parsed non-negative integers are unsigned in nlohmann::json (too large for long long
    // possibly); 1e9 or 2.0 are floats, which are refused.
    const json& c = o.required("count");
    const bool small = c.is_number_unsigned() ? c.get<unsigned long long>() <= static_cast<unsigned long long>(kMaxCount)
                                              : c.is_number_integer();
    const long long n = small ? c.get<long long>() : 0;
    if (n < 1 || n > kMaxCount) {
      throw InputError(o.key("count"), show(c), fmt::format("must be an integer in [1, {}]", kMaxCount));
    }
    a.count = static_cast<int>(n);
  }
  a.drive = parse_drive(o.required("drive"), o.key("drive"), model);
  if (a.drive.type == Drive::Type::kTca && o.has("pre_elongation_m")) {
    a.pre_elongation_m = o.number("pre_elongation_m");
  }
  a.rest_length_m = rest_length(o, a, model);
  return a;
}

}  // namespace

// ---------------------------------------------------------------------------------------

tca::Material parse_material(const nlohmann::json& j, const std::string& key) {
  const Obj o(j, key,
              {"name", "comment", "source", "reference_temperature_degC", "youngs_modulus_Pa",
               "shear_modulus_Pa", "diameter", "f12_form", "valid_range_degC"});
  tca::Material m;
  m.name = o.optional_string("name");
  if (m.name.empty()) m.name = "inline";
  m.source = o.nonempty_string("source");
  const double t_ref_degC = o.number("reference_temperature_degC");
  m.reference_temperature_K = above_absolute_zero_K(t_ref_degC, o.key("reference_temperature_degC"));
  m.youngs_modulus_Pa = parse_property(o, "youngs_modulus_Pa");
  m.shear_modulus_Pa = parse_property(o, "shear_modulus_Pa");

  const json& dj = o.required("diameter");
  const Obj d(dj, o.key("diameter"), {"linear_expansion_1_K", "ratio_polynomial_degC"});
  const bool lin = d.has("linear_expansion_1_K");
  const bool poly = d.has("ratio_polynomial_degC");
  if (lin == poly) {
    throw InputError(d.path(), show(dj),
                     "must give exactly one of linear_expansion_1_K or ratio_polynomial_degC");
  }
  if (lin) {
    m.diameter.type = tca::DiameterLaw::Type::kLinearExpansion;
    m.diameter.linear_expansion_1_K = d.number("linear_expansion_1_K");
  } else {
    m.diameter.type = tca::DiameterLaw::Type::kRatioPolynomial;
    const json& c = d.required("ratio_polynomial_degC");
    if (!c.is_array() || c.empty()) {
      throw InputError(d.key("ratio_polynomial_degC"), show(c),
                       "must be a non-empty array of coefficients [c0, c1, ...]");
    }
    for (std::size_t i = 0; i < c.size(); ++i) {
      m.diameter.ratio_polynomial.coefficients.push_back(
          as_number(c[i], fmt::format("{}[{}]", d.key("ratio_polynomial_degC"), i)));
    }
    const double p_ref = m.diameter.ratio_polynomial.value(m.reference_temperature_K);
    require(p_ref > 0.0, d.key("ratio_polynomial_degC"), show(c),
            fmt::format("must be positive at reference_temperature_degC (it is {} there and "
                        "divides the ratio)", p_ref));
  }
  if (o.has("f12_form")) m.f12_form = parse_f12_form(o);

  {
    const Eigen::Vector2d r = o.vector2("valid_range_degC");
    const std::string rk = o.key("valid_range_degC");
    above_absolute_zero_K(r[0], rk + "[0]");
    require(r[1] > r[0], rk, show(o.required("valid_range_degC")), "must satisfy lo < hi");
    m.min_temperature_K = units::degC_to_K(r[0]);
    m.max_temperature_K = units::degC_to_K(r[1]);
    require(m.reference_temperature_K >= m.min_temperature_K &&
                m.reference_temperature_K <= m.max_temperature_K,
            o.key("reference_temperature_degC"), t_ref_degC,
            fmt::format("must lie inside valid_range_degC [{}, {}]", r[0], r[1]));
    for (int i = 0; i < kMaterialRangeSamples; ++i) {
      const double t = m.min_temperature_K +
                       (m.max_temperature_K - m.min_temperature_K) * i / (kMaterialRangeSamples - 1);
      check_material_positive_at(m, t, key);
    }
  }
  check_material_positive_at(m, m.reference_temperature_K, key);
  return m;
}

std::string data_directory() {
  if (const char* env = std::getenv("TCASIM_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return TCASIM_DATA_DIR;
}

tca::Material load_material(const std::string& name, const std::string& key) {
  const bool safe = !name.empty() && name.front() != '.' &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' ||
                             c == '-';
                    });
  require(safe, key, quote(name),
          "must be a shipped material name (letters, digits, '.', '_', '-'), not a path");
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(data_directory()) / "materials";
  const fs::path file = dir / (name + ".json");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    std::vector<std::string> available;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().extension() == ".json") available.push_back(entry.path().stem().string());
    }
    std::sort(available.begin(), available.end());
    throw InputError(key, quote(name),
                     fmt::format("names no shipped material: {} does not exist (available: {})",
                                 file.string(),
                                 available.empty() ? std::string("none")
                                                   : fmt::format("{}", fmt::join(available, ", "))));
  }
  const json doc = read_json_file(file.string(), key);
  tca::Material m = parse_material(doc, file.string() + ":");
  m.name = name;
  return m;
}

RodModel parse_scenario(const nlohmann::json& doc, const std::string& base_dir) {
  // The schema is checked first so that a file of another kind gets the right message.
  const std::string schema = peek_choice(doc, "", "schema", {kScenarioSchema});
  const Obj o(doc, "",
              {"schema", "name", "comment", "body", "gravity_m_s2", "tip_load", "tip_constraint",
               "base", "tcas", "actuators"});
  RodModel m;
  m.schema = schema;
  m.name = o.nonempty_string("name");
  m.comment = o.optional_string("comment");

  const Obj body(o.required("body"), "body",
                 {"length_m", "section", "material", "reference_curvature_1_m"});
  m.length_m = body.positive("length_m");
  m.section = parse_section(body.required("section"), body.key("section"));
  const Obj mat(body.required("material"), body.key("material"),
                {"youngs_modulus_Pa", "poisson_ratio", "density_kg_m3"});
  m.material = parse_body_material(mat);
  if (body.has("reference_curvature_1_m")) {
    m.reference_curvature_B_1_m = body.vector3("reference_curvature_1_m");
  }

  if (o.has("gravity_m_s2")) {
    m.gravity_W_m_s2 = o.vector3("gravity_m_s2");
    if (!m.gravity_W_m_s2.isZero(0.0) && !mat.has("density_kg_m3")) {
      throw InputError(mat.key("density_kg_m3"), "(missing)",
                       "is required when gravity_m_s2 is non-zero");
    }
  }
  if (o.has("tip_load")) {
    const Obj tl(o.required("tip_load"), "tip_load", {"force_N", "moment_Nm"});
    if (tl.has("force_N")) m.tip_force_W_N = tl.vector3("force_N");
    if (tl.has("moment_Nm")) m.tip_moment_W_Nm = tl.vector3("moment_Nm");
  }
  if (o.has("tip_constraint")) {
    const Obj tc(o.required("tip_constraint"), "tip_constraint", {"position_m", "normal"});
    TipConstraint c;
    c.position_W_m = tc.vector3("position_m");
    if (tc.has("normal")) {
      const Eigen::Vector3d n = tc.vector3("normal");
      require(n.norm() > 0.0, tc.key("normal"), show(tc.required("normal")), "must be non-zero");
      c.normal_W = n.normalized();
    }
    m.tip_constraint = c;
  }
  if (o.has("base")) {
    const Obj b(o.required("base"), "base", {"position_m", "rotation"});
    if (b.has("position_m")) m.base_position_W_m = b.vector3("position_m");
    if (b.has("rotation")) m.R_WB0 = parse_rotation(b, "rotation");
  }
  if (o.has("tcas")) m.tcas = parse_tcas(o.required("tcas"), "tcas", base_dir);

  if (o.has("actuators")) {
    const json& acts = o.required("actuators");
    if (!acts.is_array()) {
      throw InputError("actuators", show(acts),
                       fmt::format("must be an array of actuator objects, not {}", type_name(acts)));
    }
    if (acts.size() > kMaxActuators) {
      throw InputError("actuators", fmt::format("(an array of {} actuators)", acts.size()),
                       fmt::format("must have at most {} actuators", kMaxActuators));
    }
    for (std::size_t i = 0; i < acts.size(); ++i) {
      const std::string path = fmt::format("actuators[{}]", i);
      Actuator a = parse_actuator(acts[i], path, m);
      for (std::size_t k = 0; k < m.actuators.size(); ++k) {
        require(m.actuators[k].name != a.name, path + ".name", quote(a.name),
                fmt::format("is not unique (also actuators[{}].name)", k));
      }
      m.actuators.push_back(std::move(a));
    }
  }
  return m;
}

RodModel read_scenario(const std::string& path) {
  const json doc = read_json_file(path, "scenario file");
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_scenario(doc, dir.empty() ? "." : dir);
}

std::map<std::string, std::shared_ptr<const tca::Tca>> read_tcas(const std::string& path) {
  const json doc = read_json_file(path, "TCA file");
  const std::string dir_s = std::filesystem::path(path).parent_path().string();
  const std::string dir = dir_s.empty() ? "." : dir_s;
  const std::string schema = peek_choice(doc, "", "schema", {kTcasSchema, kScenarioSchema});
  if (schema == kScenarioSchema) return parse_scenario(doc, dir).tcas;
  const Obj o(doc, "", {"schema", "name", "comment", "tcas"});
  (void)o.nonempty_string("name");
  (void)o.optional_string("comment");
  auto tcas = parse_tcas(o.required("tcas"), "tcas", dir);
  require(!tcas.empty(), "tcas", "{}", "must define at least one TCA");
  return tcas;
}

}  // namespace tcasim::rod
