#pragma once
// Internal to src/rod: the strict JSON reading shared by the scenario reader's parts
// (scenario.cpp: documents, materials; scenario_body.cpp: section, body material, base
// rotation; scenario_tca.cpp: TCA laws; scenario_actuators.cpp: routing, drives, rest
// lengths). Every malformed input throws InputError naming key path, value and rule.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/time_profile.hpp"
#include "rod/model.hpp"
#include "tca/tca.hpp"

namespace tcasim::rod::scenario_detail {

using json = nlohmann::json;

/// Segment fractions are typed as decimals; their sum must be 1 up to this (far above
/// round-off of a few terms, far below any intended fraction).
inline constexpr double kFractionSumTolerance = 1e-9;
/// base.rotation: max |R^T R - I| and |det R - 1| allowed (10 typed digits per entry).
inline constexpr double kRotationTolerance = 1e-9;
/// An offset exactly on the section edge counts as inside; this relative slack absorbs
/// the round-off of the half-extent computation.
inline constexpr double kEdgeRelativeTolerance = 1e-12;
/// Longest value text quoted in a message.
inline constexpr std::size_t kMaxValueChars = 80;
/// Number of temperatures at which a material law is checked over its valid range.
inline constexpr int kMaterialRangeSamples = 201;
/// A TCA's coiled length must equal its string's reference path length within this
/// relative amount unless the actuator gives pre_elongation_m (docs/scenario-format.md):
/// far above the round-off of the path length, below any intended pre-elongation (1 um on 1 m).
inline constexpr double kCoiledLengthRelativeTolerance = 1e-6;
/// Upper bounds on counts, each with its reason. Parallel strings of one actuator: a
/// U-shaped TCA is 2 and each string needs its own channel in the section, so more than
/// 1000 cannot be a string actuator.
inline constexpr int kMaxCount = 1000;
/// Actuators of one rod: the shooting Newton system is dense in the TCA tensions (6 + n
/// unknowns) and every right-hand side loops over all strings; the paper's robots have
/// 1 to 4, and 256 keeps one solve within seconds.
inline constexpr std::size_t kMaxActuators = 256;
/// Segments of one TCA drive: every tension evaluation solves the series of all segments;
/// 1000 resolves any temperature profile far below the TCA's own length scale.
inline constexpr std::size_t kMaxSegments = 1000;

inline const std::string kScenarioSchema = "tcasim.scenario/1";
inline const std::string kTcasSchema = "tcasim.tcas/1";

inline std::string join_path(const std::string& prefix, const std::string& key) {
  if (prefix.empty()) return key;
  if (prefix.back() == ':') return prefix + key;
  return prefix + "." + key;
}

inline std::string show(const json& j) {
  std::string s = j.dump();
  if (s.size() > kMaxValueChars) s = s.substr(0, kMaxValueChars - 3) + "...";
  return s;
}

inline std::string quote(const std::string& s) { return json(s).dump(); }

/// Human-readable name of a JSON value's type, for "must be a number, not a string".
inline std::string type_name(const json& j) { return j.type_name(); }

inline double as_number(const json& v, const std::string& key) {
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
        throw InputError(
            key(it.key()), show(it.value()),
            fmt::format("is not an allowed key here (allowed: {})", fmt::join(allowed, ", ")));
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
inline std::string peek_choice(const json& j, const std::string& path, const std::string& k,
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
// Readers of the parts (scenario_body.cpp, scenario_tca.cpp, scenario_actuators.cpp).

/// The `section` object (shape, dimensions, optional torsion constant) of a body of length
/// length_m; each dimension a number or a profile along s.
Section parse_section(const json& j, const std::string& path, double length_m);
/// The body's material (E, Poisson ratio, density, viscosity; E, density and viscosity
/// numbers or profiles along s).
BodyMaterial parse_body_material(const Obj& o, double length_m);

/// What a profile's values must satisfy.
enum class ValueRule { kPositive, kNonNegative, kAny };
/// A number or a profile {"s_m": [...], "values": [...]} (docs/scenario-format.md "Profiles
/// along the body") at `key` on a body of length length_m: s_m from 0 to length_m, never
/// decreasing, each s at most twice, as many values as s, each satisfying `rule`.
Profile parse_profile(const json& v, const std::string& key, double length_m, ValueRule rule);
/// parse_profile of the required key k of o.
Profile parse_profile_key(const Obj& o, const std::string& k, double length_m, ValueRule rule);
/// body.reference_curvature_1_m (key k of o): three components, each a number or a profile.
std::array<Profile, 3> parse_reference_curvature(const Obj& o, const std::string& k,
                                                 double length_m);
/// A row-major 3x3 rotation at key k (orthonormal to kRotationTolerance, det +1).
Eigen::Matrix3d parse_rotation(const Obj& o, const std::string& k);

/// A temperature polynomial property (degC) of a TCA material.
tca::PolynomialDegC parse_property(const Obj& o, const std::string& k);
/// The material's optional Eq. (4) factor form.
tca::F12Form parse_f12_form(const Obj& o);
/// degC -> K, refusing temperatures at or below absolute zero.
double above_absolute_zero_K(double t_degC, const std::string& key);
/// Checks that the material's moduli and diameter ratio are positive at t_K.
void check_material_positive_at(const tca::Material& m, double t_K, const std::string& key);
/// The `tcas` object: TCAs by id.
std::map<std::string, std::shared_ptr<const tca::Tca>> parse_tcas(const json& j,
                                                                  const std::string& path,
                                                                  const std::string& base_dir);

/// One entry of `actuators` (routing, count, drive, rest length) on the body `model`.
Actuator parse_actuator(const json& j, const std::string& path, const RodModel& model);

/// The top-level `probes` list (docs/scenario-format.md "Probes and frames") on a body of
/// length body_length_m (scenario_probes.cpp).
std::vector<Probe> parse_probes(const json& j, const std::string& path, double body_length_m);
/// The `obstacles` list (docs/scenario-format.md "Obstacles"; rod/scenario_obstacles.cpp):
/// shapes and their keys only; check_obstacles (rod/obstacle.hpp) then checks them against
/// the body.
std::vector<Obstacle> parse_obstacles(const json& j, const std::string& path);
/// A name that can stand in a CSV header unquoted: letters, digits, '_', '-', '.'.
bool csv_safe(const std::string& name);

// ---------------------------------------------------------------------------------------
// Time profiles and electro-thermal drives (scenario_time_profiles.cpp, scenario_thermal.cpp).

/// A number (constant) or a time profile object at `key` (docs/scenario-format.md "Time
/// profiles"); errors name the key path inside the profile.
TimeProfile parse_time_profile(const json& v, const std::string& key);
/// An array of 3 components at key k, each a number or a time profile.
std::array<TimeProfile, 3> parse_profile_vector3(const Obj& o, const std::string& k);
/// The three components at time t_s.
Eigen::Vector3d values_at(const std::array<TimeProfile, 3>& p, double t_s);

/// The `thermal` blocks of the `tcas` object (TCAs without one are absent), by TCA id.
std::map<std::string, tca::ThermalParameters> parse_tca_thermals(
    const json& tcas, const std::string& path,
    const std::map<std::string, std::shared_ptr<const tca::Tca>>& parsed);

/// The `electric` object of a drive (or of a segment) at `path` for a segment of length
/// fraction f of TCA `tca_id`: the input, its profile, the segment's share of the thermal
/// parameters; also returns the steady temperature at t = 0 [K] in `steady_K`, refusing a
/// drive without one (runaway) or with one outside the material's valid range.
ElectricSegment parse_electric(const json& j, const std::string& path, const std::string& tca_id,
                               double fraction, const RodModel& model, double& steady_K);

/// The file <data directory>/<folder>/<name>.json of a shipped data set (`what`: "material",
/// "thermal data set"), for load_material and the thermal data sets: InputError at `key` for
/// a name that is a path or names no file (the message lists the available names).
std::filesystem::path shipped_data_file(const std::string& folder, const std::string& what,
                                        const std::string& name, const std::string& key);

}  // namespace tcasim::rod::scenario_detail
