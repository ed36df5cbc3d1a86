// Scenario reader: TCA laws (the `tcas` object) and TCA material properties.
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
// TCAs

std::shared_ptr<const tca::Tca> parse_tca(const json& j, const std::string& path,
                                          const std::string& base_dir) {
  (void)base_dir;
  const Obj o(j, path,
              {"kind", "coiled_length_m", "fiber_length_m", "pitch_angle_deg", "outer_diameter_m",
               "twist_turns", "f12_form", "material", "comment", "thermal", "fiber_diameter_m",
               "coil_count", "coils_per_m"});
  tca::Parameters p;
  p.kind = o.choice("kind", {"extension", "contraction"}) == "extension" ? tca::Kind::kExtension
                                                                         : tca::Kind::kContraction;
  p.coiled_length_m = o.positive("coiled_length_m");
  const bool has_l = o.has("fiber_length_m");
  const bool has_alpha = o.has("pitch_angle_deg");
  const bool has_d0 = o.has("fiber_diameter_m");
  const bool has_count = o.has("coil_count");
  const bool has_per_m = o.has("coils_per_m");
  if (has_l && has_alpha) {
    throw InputError(o.key("pitch_angle_deg"), show(o.required("pitch_angle_deg")),
                     "must not be given together with fiber_length_m (give exactly one)");
  }
  if (!has_d0) {
    // The paper's conversions derive n from l and D: a coil count needs the measured d0.
    for (const char* k : {"coil_count", "coils_per_m"}) {
      if (o.has(k)) {
        throw InputError(o.key(k), show(o.required(k)),
                         "requires fiber_diameter_m (without it n = 2 cos(alpha0) l/(pi D) follows "
                         "from fiber_length_m or pitch_angle_deg)");
      }
    }
    if (!has_l && !has_alpha) {
      throw InputError(o.key("fiber_length_m"), "(missing)",
                       "is required unless pitch_angle_deg is given (give exactly one)");
    }
  } else if (!has_l && !has_alpha && !has_count && !has_per_m) {
    throw InputError(o.key("fiber_length_m"), "(missing)",
                     "is required unless pitch_angle_deg, coil_count or coils_per_m is given "
                     "(with fiber_diameter_m, one of them determines the helix)");
  }
  double alpha_rad = 0.0;
  if (has_l) {
    p.fiber_length_m = o.positive("fiber_length_m");
  } else if (has_alpha) {
    const double alpha_deg = o.number("pitch_angle_deg");
    require(alpha_deg > 0.0 && alpha_deg < 90.0, o.key("pitch_angle_deg"), alpha_deg,
            "must lie in (0, 90)");
    alpha_rad = units::deg_to_rad(alpha_deg);
    p.fiber_length_m = tca::fiber_length_from_pitch(p.coiled_length_m, alpha_rad);
  }
  p.outer_diameter_m = o.positive("outer_diameter_m");
  p.twist_turns = o.positive("twist_turns");
  if (has_d0) {
    const double d0 = o.positive("fiber_diameter_m");
    const double D = p.outer_diameter_m, L = p.coiled_length_m;
    require(2.0 * d0 < D, o.key("fiber_diameter_m"), d0,
            fmt::format("must be < outer_diameter_m/2 = {}: a fiber this thick leaves no coil "
                        "(inner diameter D - 2 d0 must be > 0)",
                        format_value(0.5 * D)));
    p.fiber_diameter_m = d0;
    const double Dm = D - d0;  // mean coil diameter
    // The coil count n, from coil_count or coils_per_m x L (both: they must agree).
    std::optional<double> n;
    std::string n_key;
    if (has_count) {
      n = o.positive("coil_count");
      n_key = "coil_count";
    }
    if (has_per_m) {
      const double n_per = o.positive("coils_per_m") * L;
      if (n) {
        require(
            std::abs(n_per - *n) <= tca::kGeometryRelativeTolerance * *n, o.key("coils_per_m"),
            o.positive("coils_per_m"),
            fmt::format("gives coils_per_m x coiled_length_m = {} coils, which disagrees with "
                        "coil_count = {} by more than {} relative",
                        format_value(n_per), format_value(*n), tca::kGeometryRelativeTolerance));
      } else {
        n = n_per;
        n_key = "coils_per_m";
      }
    }
    if (n) {
      if (!has_l && !has_alpha) {
        // [docs/conventions.md "Measured fiber diameter"] l^2 = (pi Dm n)^2 + L^2.
        p.fiber_length_m = tca::fiber_length_from_coil_count(L, Dm, *n);
      } else if (!has_l || p.fiber_length_m > L) {  // (l <= L: refused by tca::Tca, naming l)
        // Over-determined: the helix of l (or alpha0) and Dm has n = l cos(alpha0)/(pi Dm).
        const std::string other = has_l ? "fiber_length_m" : "pitch_angle_deg";
        const double n_geometry =
            has_l ? std::sqrt(p.fiber_length_m * p.fiber_length_m - L * L) / (units::kPi * Dm)
                  : tca::coil_count_from_pitch(L, Dm, alpha_rad);
        require(std::abs(*n - n_geometry) <= tca::kGeometryRelativeTolerance * n_geometry,
                o.key(n_key), o.positive(n_key),
                fmt::format("disagrees with {} = {}: that helix (mean diameter outer_diameter_m - "
                            "fiber_diameter_m = {} m) has n = {} coils; the difference exceeds "
                            "{} relative",
                            other, show(o.required(other)), format_value(Dm),
                            format_value(n_geometry), tca::kGeometryRelativeTolerance));
      }
    }
  }

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

}  // namespace

tca::PolynomialDegC parse_property(const Obj& o, const std::string& k) {
  const json& v = o.required(k);
  tca::PolynomialDegC p;
  if (v.is_number()) {
    p.coefficients = {as_number(v, o.key(k))};
    return p;
  }
  if (!v.is_object()) {
    throw InputError(o.key(k), show(v), "must be a number or {\"polynomial_degC\": [c0, c1, ...]}");
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
  require(
      t_degC > -units::kZeroCelsius_K, key, t_degC,
      t_degC < -units::kZeroCelsius_K ? "is below absolute zero" : "is not above absolute zero");
  return units::degC_to_K(t_degC);
}

/// Checks that E, G and the diameter ratio are positive at `t_K` (a material law that
/// is not cannot be evaluated there).
void check_material_positive_at(const tca::Material& m, double t_K, const std::string& key) {
  // Called for every sampled temperature of every material: the messages (key paths and
  // formatted rules) are built only when a check fails.
  const double t_degC = units::K_to_degC(t_K);
  const double E = m.youngs_modulus_Pa.value(t_K);
  const double G = m.shear_modulus_Pa.value(t_K);
  if (!(E > 0.0)) {
    throw_input_error(join_path(key, "youngs_modulus_Pa"), E,
                      fmt::format("must be positive (value at {:.10g} degC)", t_degC));
  }
  if (!(G > 0.0)) {
    throw_input_error(join_path(key, "shear_modulus_Pa"), G,
                      fmt::format("must be positive (value at {:.10g} degC)", t_degC));
  }
  if (m.diameter.type == tca::DiameterLaw::Type::kLinearExpansion) {
    const double ratio = 1.0 + m.diameter.linear_expansion_1_K * (t_K - m.reference_temperature_K);
    if (!(ratio > 0.0)) {
      throw_input_error(
          join_path(key, "diameter.linear_expansion_1_K"), m.diameter.linear_expansion_1_K,
          fmt::format("gives a non-positive diameter ratio {} at {:.10g} degC", ratio, t_degC));
    }
  } else {
    const double ratio = m.diameter.ratio_polynomial.value(t_K) /
                         m.diameter.ratio_polynomial.value(m.reference_temperature_K);
    if (!(ratio > 0.0)) {
      throw_input_error(
          join_path(key, "diameter.ratio_polynomial_degC"), ratio,
          fmt::format("is the diameter ratio at {:.10g} degC; it must be positive", t_degC));
    }
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

}  // namespace tcasim::rod::scenario_detail
