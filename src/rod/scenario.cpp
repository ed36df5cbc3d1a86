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
#include "rod/internal/scenario_reading.hpp"
#include "rod/json_file.hpp"
#include "rod/reference_path.hpp"

namespace tcasim::rod {

using namespace scenario_detail;

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
  m.reference_temperature_K =
      above_absolute_zero_K(t_ref_degC, o.key("reference_temperature_degC"));
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
                        "divides the ratio)",
                        p_ref));
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
      const double t = m.min_temperature_K + (m.max_temperature_K - m.min_temperature_K) * i /
                                                 (kMaterialRangeSamples - 1);
      check_material_positive_at(m, t, key);
    }
  }
  check_material_positive_at(m, m.reference_temperature_K, key);
  return m;
}

std::filesystem::path scenario_detail::shipped_data_file(const std::string& folder,
                                                         const std::string& what,
                                                         const std::string& name,
                                                         const std::string& key) {
  const bool safe =
      !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
      });
  require(safe, key, quote(name),
          "must be a shipped " + what + " name (letters, digits, '.', '_', '-'), not a path");
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(data_directory()) / folder;
  const fs::path file = dir / (name + ".json");
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    std::vector<std::string> available;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      if (entry.path().extension() == ".json") available.push_back(entry.path().stem().string());
    }
    std::sort(available.begin(), available.end());
    throw InputError(
        key, quote(name),
        fmt::format("names no shipped {}: {} does not exist (available: {})", what, file.string(),
                    available.empty() ? std::string("none")
                                      : fmt::format("{}", fmt::join(available, ", "))));
  }
  return file;
}

tca::Material load_material(const std::string& name, const std::string& key) {
  const std::filesystem::path file = shipped_data_file("materials", "material", name, key);
  const json doc = read_json_file(file.string(), key);
  tca::Material m = parse_material(doc, file.string() + ":");
  m.name = name;
  return m;
}

RodModel parse_scenario(const nlohmann::json& doc, const std::string& base_dir) {
  // The schema is checked first so that a file of another kind gets the right message.
  const std::string schema = peek_choice(doc, "", "schema", {kScenarioSchema});
  const Obj o(doc, "",
              {"schema", "name", "comment", "body", "gravity_m_s2", "tip_load", "tip_mass_kg",
               "tip_constraint", "base", "tcas", "actuators", "probes", "obstacles"});
  RodModel m;
  m.schema = schema;
  m.name = o.nonempty_string("name");
  m.comment = o.optional_string("comment");

  const Obj body(o.required("body"), "body",
                 {"length_m", "section", "material", "reference_curvature_1_m"});
  m.length_m = body.positive("length_m");
  m.section = parse_section(body.required("section"), body.key("section"), m.length_m);
  const Obj mat(body.required("material"), body.key("material"),
                {"youngs_modulus_Pa", "poisson_ratio", "density_kg_m3", "viscosity_Pa_s"});
  m.material = parse_body_material(mat, m.length_m);
  if (body.has("reference_curvature_1_m")) {
    m.reference_curvature_profile =
        parse_reference_curvature(body, "reference_curvature_1_m", m.length_m);
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
    if (tl.has("force_N")) {
      m.tip_force_profile_W_N = parse_profile_vector3(tl, "force_N");
      m.tip_force_W_N = values_at(m.tip_force_profile_W_N, 0.0);
    }
    if (tl.has("moment_Nm")) {
      m.tip_moment_profile_W_Nm = parse_profile_vector3(tl, "moment_Nm");
      m.tip_moment_W_Nm = values_at(m.tip_moment_profile_W_Nm, 0.0);
    }
  }
  if (o.has("tip_mass_kg")) {
    m.tip_mass_kg = o.number("tip_mass_kg");
    require(m.tip_mass_kg >= 0.0, "tip_mass_kg", m.tip_mass_kg, "must be >= 0");
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
  if (o.has("tcas")) {
    m.tcas = parse_tcas(o.required("tcas"), "tcas", base_dir);
    m.tca_thermal = parse_tca_thermals(o.required("tcas"), "tcas", m.tcas);
  }

  if (o.has("actuators")) {
    const json& acts = o.required("actuators");
    if (!acts.is_array()) {
      throw InputError(
          "actuators", show(acts),
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
  if (o.has("probes")) m.probes = parse_probes(o.required("probes"), "probes", m.length_m);
  if (o.has("obstacles")) {
    m.obstacles = parse_obstacles(o.required("obstacles"), "obstacles");
    check_obstacles(m);
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
  (void)parse_tca_thermals(o.required("tcas"), "tcas", tcas);  // validated, not returned
  require(!tcas.empty(), "tcas", "{}", "must define at least one TCA");
  return tcas;
}

}  // namespace tcasim::rod
