// The TCA model of [Pawlowski2019] Section II with the decisions of
// docs/conventions.md "TCA model ([Pawlowski2019] Section II)" (see tca.hpp).
#include "tca/tca.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "common/root_finding.hpp"
#include "common/units.hpp"

namespace tcasim::tca {
namespace {

using units::kPi;

/// Grid used to find the sign change nearest the closed state before Brent refines it:
/// coarse enough to be cheap, fine enough that two roots never share a cell in practice
/// (the balance h(delta) is monotone for any load the fiber survives).
constexpr int kScanIntervals = 16;
/// Absolute tolerance of the elongation root [m]: far below any measurable length.
constexpr double kElongationTol_m = 1e-16;
/// Absolute tolerance of temperature roots [K].
constexpr double kTemperatureTol_K = 1e-11;
/// Sum of segment fractions must be 1 within this (round-off of user decimals).
constexpr double kFractionSumTol = 1e-9;

/// A temperature for messages [degC]: 10 significant digits hide the K<->degC round-off.
std::string degC(double t_K) { return fmt::format("{:.10g}", units::K_to_degC(t_K)); }

/// f11 and P = f12 tau (Eqs. (1), (3), (4)) and their partial derivatives with respect to
/// alpha and T, at sin(alpha) = x and material state m.
struct LawTerms {
  double f11, df11_dalpha, df11_dT;
  double p, dp_dalpha, dp_dT;
};

LawTerms law_terms(const Tca& tca, double x, const MaterialState& m) {
  const double l = tca.parameters().fiber_length_m;
  const double n = tca.coil_count();
  const double r = m.diameter_ratio;
  const double dr = m.dratio_dT_1_K;
  const double d = tca.initial_fiber_diameter_m() * r;
  const double d2 = d * d;
  const double s2 = x * x, c2 = std::max(0.0, 1.0 - s2);  // x may round to just above 1
  const double sc = x * std::sqrt(c2);
  const double gi = 1.0 / m.shear_modulus_Pa, ei = 1.0 / m.youngs_modulus_Pa;
  const double dgi = -m.dG_dT_Pa_K * gi * gi, dei = -m.dE_dT_Pa_K * ei * ei;

  // [Pawlowski2019] Eq. (3): f11 = 8n/(pi^3 d^4) (l/n)^3 (cos^4/G + 2 sin^2 cos^2/E)
  //                                + 8n/(pi d^2) (l/n) (cos^2/(2G) + sin^2/(2E))
  //                              = A Q1 + B Q2, A = 8 l^3/(pi^3 n^2 d^4), B = 8 l/(pi d^2).
  const double a = 8.0 * l * l * l / (kPi * kPi * kPi * n * n * d2 * d2);
  const double b = 8.0 * l / (kPi * d2);
  const double q1 = c2 * c2 * gi + 2.0 * s2 * c2 * ei;
  const double q2 = 0.5 * (c2 * gi + s2 * ei);
  LawTerms t{};
  t.f11 = a * q1 + b * q2;
  const double dq1_da = sc * (-4.0 * c2 * gi + 4.0 * (c2 - s2) * ei);
  const double dq2_da = sc * (ei - gi);
  t.df11_dalpha = a * dq1_da + b * dq2_da;
  // d = d0 r(T): dA/dT = -4 A r'/r, dB/dT = -2 B r'/r.
  const double dq1_dT = c2 * c2 * dgi + 2.0 * s2 * c2 * dei;
  const double dq2_dT = 0.5 * (c2 * dgi + s2 * dei);
  t.df11_dT = -4.0 * a * q1 * dr / r + a * dq1_dT - 2.0 * b * q2 * dr / r + b * dq2_dT;

  // [Pawlowski2019] Eqs. (1), (4): f12 tau = k n (l/n)^2 cos^2/(pi^2 d^4 G) * G (pi d^4/32)
  // phi0 (1 - d0/d)/l = k l phi0 cos^2(alpha) (1 - 1/r)/(32 pi n): G_T and d^4 cancel.
  const double k = tca.parameters().f12_form == F12Form::kPaper ? 8.0 : 16.0;
  const double kc = k * l * tca.initial_twist_rad() / (32.0 * kPi * n);
  const double strain = 1.0 - 1.0 / r;
  t.p = kc * c2 * strain;
  t.dp_dalpha = -2.0 * sc * kc * strain;
  t.dp_dT = kc * c2 * dr / (r * r);
  return t;
}

double sin_pitch(const Tca& tca, double elongation_m) {
  // [Pawlowski2019] Eq. (5): delta = l (sin(alpha) - sin(alpha0)).
  const double l = tca.parameters().fiber_length_m;
  const double x = std::sin(tca.initial_pitch_angle_rad()) + elongation_m / l;
  if (!(x > 0.0 && x < 1.0)) {
    throw DomainError(fmt::format(
        "TCA elongation delta = {} m gives sin(alpha) = {}, outside (0, 1): delta must lie in "
        "({} m, {} m) (Eq. (5))",
        elongation_m, x, -l * std::sin(tca.initial_pitch_angle_rad()),
        l * (1.0 - std::sin(tca.initial_pitch_angle_rad()))));
  }
  return x;
}

}  // namespace

const char* to_string(Kind k) { return k == Kind::kExtension ? "extension" : "contraction"; }
const char* to_string(F12Form f) { return f == F12Form::kPaper ? "paper" : "castigliano"; }

double PolynomialDegC::value(double t_K) const {
  const double t = units::K_to_degC(t_K);
  double v = 0.0;
  for (auto it = coefficients.rbegin(); it != coefficients.rend(); ++it) v = v * t + *it;
  return v;
}

double PolynomialDegC::derivative(double t_K) const {
  const double t = units::K_to_degC(t_K);
  double v = 0.0;
  for (std::size_t i = coefficients.size(); i-- > 1;)
    v = v * t + static_cast<double>(i) * coefficients[i];
  return v;
}

MaterialState Material::at(double t_K) const {
  if (!(t_K >= min_temperature_K && t_K <= max_temperature_K)) {
    throw DomainError(fmt::format(
        "temperature {} degC is outside the valid range [{}, {}] degC of TCA material '{}'",
        degC(t_K), degC(min_temperature_K), degC(max_temperature_K), name));
  }
  MaterialState s{};
  s.youngs_modulus_Pa = youngs_modulus_Pa.value(t_K);
  s.dE_dT_Pa_K = youngs_modulus_Pa.derivative(t_K);
  s.shear_modulus_Pa = shear_modulus_Pa.value(t_K);
  s.dG_dT_Pa_K = shear_modulus_Pa.derivative(t_K);
  if (diameter.type == DiameterLaw::Type::kLinearExpansion) {
    // [Pawlowski2019] Sec. II: d = d0 (1 + rho (T - T_ref)).
    s.diameter_ratio = 1.0 + diameter.linear_expansion_1_K * (t_K - reference_temperature_K);
    s.dratio_dT_1_K = diameter.linear_expansion_1_K;
  } else {
    const double p_ref = diameter.ratio_polynomial.value(reference_temperature_K);
    if (!(p_ref > 0.0)) {
      throw DomainError(fmt::format(
          "diameter ratio polynomial of TCA material '{}' is {} at the reference temperature "
          "{} degC; it must be > 0",
          name, p_ref, degC(reference_temperature_K)));
    }
    s.diameter_ratio = diameter.ratio_polynomial.value(t_K) / p_ref;
    s.dratio_dT_1_K = diameter.ratio_polynomial.derivative(t_K) / p_ref;
  }
  const auto check_positive = [&](double v, const char* what) {
    if (!(v > 0.0)) {
      throw DomainError(fmt::format("{} of TCA material '{}' is {} at {} degC; it must be > 0",
                                    what, name, v, degC(t_K)));
    }
  };
  check_positive(s.youngs_modulus_Pa, "Young's modulus E_T [Pa]");
  check_positive(s.shear_modulus_Pa, "shear modulus G_T [Pa]");
  check_positive(s.diameter_ratio, "diameter ratio d/d0");
  return s;
}

double fiber_length_from_pitch(double coiled_length_m, double pitch_angle_rad) {
  return coiled_length_m / std::sin(pitch_angle_rad);
}

double fiber_length_from_coil_count(double coiled_length_m, double mean_diameter_m,
                                    double coil_count) {
  // Unrolled helix (docs/conventions.md "Measured fiber diameter"): l^2 = (pi Dm n)^2 + L^2.
  return std::hypot(kPi * mean_diameter_m * coil_count, coiled_length_m);
}

double coil_count_from_pitch(double coiled_length_m, double mean_diameter_m,
                             double pitch_angle_rad) {
  // tan(alpha0) = L / (pi Dm n).
  return coiled_length_m / (kPi * mean_diameter_m * std::tan(pitch_angle_rad));
}

Tca::Tca(const Parameters& parameters, Material material)
    : p_(parameters), material_(std::move(material)) {
  const double L = p_.coiled_length_m, l = p_.fiber_length_m, D = p_.outer_diameter_m;
  require(L > 0.0, "coiled_length_m", L, "must be > 0");
  require(l > L, "coiled_length_m", L,
          fmt::format("must be < fiber_length_m = {}", format_value(l)));
  require(D > 0.0, "outer_diameter_m", D, "must be > 0");
  require(p_.twist_turns > 0.0, "twist_turns", p_.twist_turns, "must be > 0");
  if (!p_.fiber_diameter_m) {
    // [Pawlowski2019] Sec. II conversions, as printed ("effective" values, see conventions):
    // alpha0 = asin(L/l), n = 2 cos(alpha0) l/(pi D), phi0 = 2 pi N, d0 = 2 D L/l.
    alpha0_ = std::asin(L / l);
    n_ = 2.0 * std::cos(alpha0_) * l / (kPi * D);
    phi0_ = 2.0 * kPi * p_.twist_turns;
    d0_ = 2.0 * D * L / l;
    require(d0_ < D, "coiled_length_m", L,
            fmt::format("must be < fiber_length_m/2 = {} so that the fiber diameter d0 = 2 D L/l "
                        "is below outer_diameter_m",
                        format_value(0.5 * l)));
    require(n_ >= 1.0, "outer_diameter_m", D,
            fmt::format("gives n = 2 cos(alpha0) l/(pi D) = {} coils; must give n >= 1",
                        format_value(n_)));
    // Made closed (extension) or modelled open without a limit (contraction): -L is the flat
    // coil, the end of the domain of Eq. (5).
    closed_elongation_ = p_.kind == Kind::kExtension ? 0.0 : -L;
  } else {
    const double d0 = *p_.fiber_diameter_m;
    require(d0 > 0.0, "fiber_diameter_m", d0, "must be > 0");
    require(2.0 * d0 < D, "fiber_diameter_m", d0,
            fmt::format("must be < outer_diameter_m/2 = {}: a fiber this thick leaves no coil "
                        "(inner diameter D - 2 d0 must be > 0)",
                        format_value(0.5 * D)));
    // Helix of mean diameter Dm = D - d0 (docs/conventions.md "Measured fiber diameter"):
    // L = l sin(alpha0), pi Dm n = l cos(alpha0), phi0 = 2 pi N.
    const double Dm = D - d0;
    alpha0_ = std::asin(L / l);
    n_ = l * std::cos(alpha0_) / (kPi * Dm);
    phi0_ = 2.0 * kPi * p_.twist_turns;
    d0_ = d0;
    require(n_ >= 1.0, "fiber_length_m", l,
            fmt::format("gives n = l cos(alpha0)/(pi (D - d0)) = {} coils; must give n >= 1",
                        format_value(n_)));
    // Closed length n d0: coils of pitch L/n below the fiber diameter would overlap. A coil
    // wound closed (n d0 = L up to the measurement tolerance) sits at its closed length.
    const double closed_length_m = n_ * d0;
    require(closed_length_m <= L * (1.0 + kGeometryRelativeTolerance), "fiber_diameter_m", d0,
            fmt::format("must be <= the coil pitch L/n = {} m (n = {} coils over coiled_length_m "
                        "= {}): the coils would overlap (closed length n d0 = {} m > L, beyond "
                        "{} relative)",
                        format_value(L / n_), format_value(n_), format_value(L),
                        format_value(closed_length_m), kGeometryRelativeTolerance));
    closed_elongation_ = std::min(0.0, closed_length_m - L);
    // Twist pitch l/N (fiber length per twist turn) at least d0: the surface bias angle
    // atan(pi d0 N/l) stays below atan(pi) = 72.3 deg.
    require(l / p_.twist_turns >= d0, "twist_turns", p_.twist_turns,
            fmt::format("must be <= fiber_length_m/fiber_diameter_m = {}: a twist pitch l/N "
                        "shorter than the fiber diameter (surface bias angle above 72.3 deg) "
                        "cannot be carried by that fiber length",
                        format_value(l / d0)));
  }
  require(
      material_.min_temperature_K < material_.max_temperature_K, "material.valid_range_degC",
      fmt::format("[{}, {}]", degC(material_.min_temperature_K), degC(material_.max_temperature_K)),
      "must have lo < hi");
  const double t_ref_K = std::clamp(material_.reference_temperature_K, material_.min_temperature_K,
                                    material_.max_temperature_K);
  try {
    (void)material_.at(material_.reference_temperature_K);
    contact_stiffness_ = std::abs(tension(0.0, t_ref_K).dF_ddelta_N_m);
  } catch (const DomainError& e) {
    throw InputError("material", material_.name,
                     std::string("is invalid at its reference temperature: ") + e.what());
  }
}

double Tca::chirality() const { return p_.kind == Kind::kExtension ? 1.0 : -1.0; }

double Tca::mean_coil_diameter_m() const {
  return p_.fiber_diameter_m ? p_.outer_diameter_m - d0_ : 0.5 * p_.outer_diameter_m;
}

Coefficients Tca::coefficients(double alpha_rad, double t_K) const {
  const MaterialState m = material_.at(t_K);
  const double l = p_.fiber_length_m;
  const double d = d0_ * m.diameter_ratio;
  const double c = std::cos(alpha_rad), s = std::sin(alpha_rad);
  const double G = m.shear_modulus_Pa, E = m.youngs_modulus_Pa;
  const double ln = l / n_;
  Coefficients out{};
  // [Pawlowski2019] Eq. (3).
  out.f11_m_N = 8.0 * n_ / (kPi * kPi * kPi * std::pow(d, 4)) * ln * ln * ln *
                    (std::pow(c, 4) / G + 2.0 * s * s * c * c / E) +
                8.0 * n_ / (kPi * d * d) * ln * (c * c / (2.0 * G) + s * s / (2.0 * E));
  // [Pawlowski2019] Eq. (4) with factor 8 (as printed) or 16 (Castigliano, see conventions).
  const double k = p_.f12_form == F12Form::kPaper ? 8.0 : 16.0;
  out.f12_1_N = k * n_ / (kPi * kPi * std::pow(d, 4)) * ln * ln * c * c / G;
  // [Pawlowski2019] Eq. (1): tau = G_T J_T phi0 (1 - d0/d)/l, J_T = pi d^4/32.
  const double J = kPi * std::pow(d, 4) / 32.0;
  out.tau_Nm = G * J * phi0_ * (1.0 - d0_ / d) / l;
  return out;
}

double Tca::pitch_angle(double elongation_m) const {
  return std::asin(sin_pitch(*this, elongation_m));
}

TensionState Tca::tension(double elongation_m, double t_K) const {
  const double x = sin_pitch(*this, elongation_m);
  const MaterialState m = material_.at(t_K);
  const LawTerms t = law_terms(*this, x, m);
  const double s = chirality();
  TensionState out{};
  // [Pawlowski2019] Eq. (6): F = (delta - s f12 tau)/f11.
  out.tension_N = (elongation_m - s * t.p) / t.f11;
  // Eq. (5): d alpha/d delta = 1/(l cos(alpha)).
  const double dalpha_ddelta = 1.0 / (p_.fiber_length_m * std::sqrt(1.0 - x * x));
  out.dF_ddelta_N_m =
      (1.0 - (s * t.dp_dalpha + out.tension_N * t.df11_dalpha) * dalpha_ddelta) / t.f11;
  out.dF_dT_N_K = -(s * t.dp_dT + out.tension_N * t.df11_dT) / t.f11;
  out.pitch_angle_rad = std::asin(x);
  out.below_closed_length = has_coil_contact() && elongation_m < closed_elongation_;
  return out;
}

ElongationState Tca::free_coil_elongation(double tension_N, double t_K) const {
  const MaterialState m = material_.at(t_K);
  const double l = p_.fiber_length_m;
  const double x0 = std::sin(alpha0_);
  const double s = chirality();
  // [Pawlowski2019] Eqs. (2)+(5): h(delta) = delta - f11(alpha(delta)) F - s f12 tau = 0.
  const auto h = [&](double delta) {
    const double x = x0 + delta / l;
    const LawTerms t = law_terms(*this, x, m);
    return delta - t.f11 * tension_N - s * t.p;
  };
  const double delta_lo = -l * x0, delta_hi = l * (1.0 - x0);  // sin(alpha) = 0 and 1
  const double h0 = h(0.0);
  std::optional<roots::RootResult> root;
  if (h0 == 0.0) {
    root = roots::RootResult{0.0, 0};
  } else if (h0 < 0.0) {  // the coils open: the root nearest the closed state lies above
    root = roots::first_root(h, 0.0, delta_hi, kScanIntervals, kElongationTol_m);
  } else {
    root = roots::first_root(h, 0.0, delta_lo, kScanIntervals, kElongationTol_m);
  }
  if (!root) {
    throw DomainError(fmt::format(
        "TCA: no pitch angle in [{} deg, 90 deg] balances tension F = {} N at {} degC (Eqs. "
        "(2), (5); searched from alpha0 = {} deg toward {})",
        h0 < 0.0 ? units::rad_to_deg(alpha0_) : 0.0, tension_N, degC(t_K),
        units::rad_to_deg(alpha0_), h0 < 0.0 ? "90 deg" : "0 deg"));
  }
  ElongationState out{};
  out.elongation_m = root->x;
  out.pitch_angle_rad = std::asin(std::min(1.0, std::max(0.0, x0 + root->x / l)));
  out.coils_closed = false;
  return out;
}

ElongationState Tca::elongation(double tension_N, double t_K) const {
  ElongationState out = free_coil_elongation(tension_N, t_K);
  // Closed coils (docs/conventions.md "Closed coils"): a TCA with coil contact cannot shorten
  // below its closed length (L for the paper's extension TCA, n d0 with a measured d0).
  if (has_coil_contact() && out.elongation_m < closed_elongation_) {
    out.elongation_m = closed_elongation_;
    out.pitch_angle_rad = closed_elongation_ == 0.0 ? alpha0_ : pitch_angle(closed_elongation_);
    out.coils_closed = true;
  }
  return out;
}

double Tca::temperature_for_tension(double tension_N, double elongation_m, double t_lo_K,
                                    double t_hi_K) const {
  const auto q = [&](double t_K) { return tension(elongation_m, t_K).tension_N - tension_N; };
  const auto root = roots::first_root(q, t_lo_K, t_hi_K, kScanIntervals, kTemperatureTol_K);
  if (!root) {
    throw DomainError(fmt::format(
        "TCA: no temperature in [{} degC, {} degC] gives tension {} N at elongation {} m "
        "(tension there ranges from {} N to {} N)",
        degC(t_lo_K), degC(t_hi_K), tension_N, elongation_m,
        tension(elongation_m, t_lo_K).tension_N, tension(elongation_m, t_hi_K).tension_N));
  }
  return root->x;
}

std::optional<double> Tca::onset_temperature(double tension_N, double t_lo_K, double t_hi_K) const {
  if (!has_coil_contact()) {
    throw InputError("kind", to_string(p_.kind),
                     "has no closed-coil onset temperature (only extension TCAs and TCAs with a "
                     "measured fiber_diameter_m do)");
  }
  // The coils open where F_c(T) = F(delta_c, T) drops below the load: closed while
  // F_c(T) - F >= 0 (h(delta_c) = -f11 (F - F_c)).
  const auto q = [&](double t_K) { return tension(closed_elongation_, t_K).tension_N - tension_N; };
  if (q(t_lo_K) < 0.0) return t_lo_K;
  // One grid cell per kelvin at least: the onset is the first crossing, not any crossing.
  const int intervals = std::max(kScanIntervals, static_cast<int>(std::ceil(t_hi_K - t_lo_K)));
  const auto root = roots::first_root(q, t_lo_K, t_hi_K, intervals, kTemperatureTol_K);
  if (!root) return std::nullopt;
  return root->x;
}

namespace {
void check_segments(const std::vector<Segment>& segments) {
  require(!segments.empty(), "segments", "[]", "must list at least one segment");
  double sum = 0.0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    require(segments[i].fraction > 0.0 && segments[i].fraction <= 1.0,
            fmt::format("segments[{}].fraction", i), segments[i].fraction, "must lie in (0, 1]");
    sum += segments[i].fraction;
  }
  require(std::abs(sum - 1.0) <= kFractionSumTol, "segments",
          fmt::format("fractions summing to {}", sum), "must sum to 1");
}
}  // namespace

double series_elongation(const Tca& tca, double tension_N, const std::vector<Segment>& segments) {
  check_segments(segments);
  // A fraction f of the TCA has f11, f12 (and n, l, L) scaled by f and the same tau:
  // delta = sum_k f_k delta(F, T_k), each segment with its own closed-coil limit.
  double delta = 0.0;
  for (const Segment& s : segments) {
    delta += s.fraction * tca.elongation(tension_N, s.temperature_K).elongation_m;
  }
  return delta;
}

SeriesTensionState series_tension(const Tca& tca, double elongation_m,
                                  const std::vector<Segment>& segments) {
  check_segments(segments);
  SeriesTensionState out{};
  out.dF_dT_N_K.assign(segments.size(), 0.0);
  // If every segment had the total elongation, segment k would carry F_k = F(delta, T_k).
  // Each free-coil elongation grows with F, so the shared tension lies in [min F_k, max F_k].
  double f_lo = 0.0, f_hi = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double f = tca.tension(elongation_m, segments[k].temperature_K).tension_N;
    f_lo = (k == 0) ? f : std::min(f_lo, f);
    f_hi = (k == 0) ? f : std::max(f_hi, f);
  }
  const auto residual = [&](double f) {
    double delta = 0.0;
    for (const Segment& s : segments) {
      delta += s.fraction * tca.free_coil_elongation(f, s.temperature_K).elongation_m;
    }
    return delta - elongation_m;
  };
  double tension_N = f_lo;
  if (f_hi > f_lo) {
    // Absolute tolerance on F [N]: relative round-off level of the bracket's scale.
    const double tol = 1e-15 * std::max(std::abs(f_lo), std::abs(f_hi));
    const auto root = roots::brent(residual, f_lo, f_hi, residual(f_lo), residual(f_hi), tol);
    if (!root) {
      throw DomainError(fmt::format(
          "TCA series: no shared tension in [{} N, {} N] gives total elongation {} m (free-coil "
          "compliance not positive?)",
          f_lo, f_hi, elongation_m));
    }
    tension_N = root->x;
  }
  out.tension_N = tension_N;
  // ddelta/dF = sum f_k / k_k with k_k = dF/ddelta of segment k at its own elongation;
  // dF/dT_k = f_k (dF/dT)_k / k_k * dF/ddelta.
  double compliance = 0.0;
  std::vector<TensionState> states;
  states.reserve(segments.size());
  for (const Segment& s : segments) {
    const double dk = tca.free_coil_elongation(tension_N, s.temperature_K).elongation_m;
    states.push_back(tca.tension(dk, s.temperature_K));
    compliance += s.fraction / states.back().dF_ddelta_N_m;
  }
  out.dF_ddelta_N_m = 1.0 / compliance;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    out.dF_dT_N_K[k] =
        segments[k].fraction * states[k].dF_dT_N_K / states[k].dF_ddelta_N_m * out.dF_ddelta_N_m;
  }
  return out;
}

ContactResidual contact_residual(const Tca& tca, double tension_N, double elongation_m,
                                 const std::vector<Segment>& segments) {
  const double kc = tca.contact_stiffness_N_m();
  const bool contact = tca.has_coil_contact();
  // delta_c: 0 for the paper's extension TCA (so these lines reduce to the delta >= 0 form).
  const double dc = tca.closed_elongation_m();
  ContactResidual out{};
  if (segments.size() == 1) {
    const double t_K = segments[0].temperature_K;
    if (!contact || elongation_m >= dc) {
      const TensionState ts = tca.tension(elongation_m, t_K);
      out = {tension_N - ts.tension_N, 1.0, -ts.dF_ddelta_N_m, -ts.dF_dT_N_K};
    } else {
      // No free-coil state below the closed length: F_free continued from delta_c with the
      // slope k_c (temperature independent, so d phi/dT stays -dF_c/dT).
      const TensionState t0 = tca.tension(dc, t_K);
      out = {tension_N - t0.tension_N - kc * (elongation_m - dc), 1.0, -kc, -t0.dF_dT_N_K};
    }
    // Closed branch -k_c (delta - delta_c) where it is the larger: contact holds delta_c.
    if (contact && -kc * (elongation_m - dc) > out.phi_N) {
      out = {-kc * (elongation_m - dc), 0.0, -kc, 0.0};
    }
    return out;
  }
  check_segments(segments);
  // phi = k_c (sum_k f_k max(delta_c, e_k) - delta), e_k = e(F, T_k); a segment is closed
  // (e_k <= delta_c) exactly when F <= F_c(T_k), which needs no root finding.
  double sum = 0.0, de_dF = 0.0, de_dT = 0.0;
  for (const Segment& s : segments) {
    if (contact && tension_N <= tca.closed_force(s.temperature_K)) {
      if (dc != 0.0) sum += s.fraction * dc;  // (skipped at delta_c = 0: same numbers as before)
      continue;
    }
    const double e = tca.free_coil_elongation(tension_N, s.temperature_K).elongation_m;
    const TensionState ts = tca.tension(e, s.temperature_K);
    sum += s.fraction * e;
    // de/dF = 1 / (dF/d delta); de/dT = -(dF/dT) / (dF/d delta).
    de_dF += s.fraction / ts.dF_ddelta_N_m;
    de_dT -= s.fraction * ts.dF_dT_N_K / ts.dF_ddelta_N_m;
  }
  out = {kc * (sum - elongation_m), kc * de_dF, -kc, kc * de_dT};
  return out;
}

std::vector<SegmentContact> segment_contacts(const Tca& tca, double tension_N,
                                             const std::vector<Segment>& segments) {
  std::vector<SegmentContact> out(segments.size());
  if (!tca.has_coil_contact()) return out;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double c = tca.closed_force(segments[k].temperature_K) - tension_N;
    if (c > 0.0) out[k] = {true, c};
  }
  return out;
}

}  // namespace tcasim::tca
