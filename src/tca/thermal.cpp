#include "tca/thermal.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"

namespace tcasim::tca {

ThermalParameters ThermalParameters::fraction(double f) const {
  ThermalParameters s = *this;
  s.heat_capacity_J_K *= f;
  s.conductance_W_K *= f;
  s.resistance_ohm *= f;
  return s;
}

double ThermalParameters::resistance_ohm_at(double T_K) const {
  const double R =
      resistance_ohm * (1.0 + resistance_temperature_coefficient_1_K * (T_K - ambient_K));
  if (!(R > 0.0)) {
    throw DomainError(fmt::format(
        "TCA resistance R(T) = R0 (1 + alpha_R (T - T_amb)) = {} ohm at T = {} K is not positive "
        "(R0 = {} ohm, alpha_R = {} 1/K, T_amb = {} K)",
        R, T_K, resistance_ohm, resistance_temperature_coefficient_1_K, ambient_K));
  }
  return R;
}

const char* key_name(ElectricInput input) {
  switch (input) {
    case ElectricInput::kVoltage:
      return "voltage_V";
    case ElectricInput::kCurrent:
      return "current_A";
    case ElectricInput::kPower:
      return "power_W";
  }
  return "?";
}

JoulePower joule_power(const ThermalParameters& p, ElectricInput input, double u, double T_K) {
  JoulePower j;
  if (input == ElectricInput::kPower) {
    j.power_W = u;
    return j;
  }
  const double R = p.resistance_ohm_at(T_K);
  const double dR = p.resistance_ohm * p.resistance_temperature_coefficient_1_K;
  if (input == ElectricInput::kCurrent) {
    // P = i^2 R(T)
    j.power_W = u * u * R;
    j.dP_dT_W_K = u * u * dR;
  } else {
    // P = v^2 / R(T)
    j.power_W = u * u / R;
    j.dP_dT_W_K = -j.power_W * dR / R;
  }
  return j;
}

HeatingRate heating_rate(const ThermalParameters& p, ElectricInput input, double u, double T_K) {
  // C dT/dt = P(T) - hA (T - T_amb)
  const JoulePower j = joule_power(p, input, u, T_K);
  HeatingRate h;
  h.dT_dt_K_s = (j.power_W - p.conductance_W_K * (T_K - p.ambient_K)) / p.heat_capacity_J_K;
  h.d_dT_1_s = (j.dP_dT_W_K - p.conductance_W_K) / p.heat_capacity_J_K;
  return h;
}

SteadyTemperature steady_temperature(const ThermalParameters& p, ElectricInput input, double u) {
  SteadyTemperature s;
  const double hA = p.conductance_W_K, R0 = p.resistance_ohm;
  const double a = p.resistance_temperature_coefficient_1_K;
  double x = 0.0;  // T - T_amb
  switch (input) {
    case ElectricInput::kPower:
      x = u / hA;
      break;
    case ElectricInput::kCurrent: {
      // hA x = i^2 R0 (1 + alpha_R x)
      const double gain = u * u * R0 * a;  // d(Joule power)/dT
      if (gain >= hA) {
        s.reason = fmt::format(
            "has no steady temperature: i^2 R0 alpha_R = {:.6g} W/K >= hA = {:.6g} W/K, the "
            "Joule power grows with temperature faster than the losses (thermal runaway)",
            gain, hA);
        return s;
      }
      x = u * u * R0 / (hA - gain);
      break;
    }
    case ElectricInput::kVoltage: {
      // hA x (1 + alpha_R x) = v^2 / R0; with q = v^2 / (R0 hA): alpha_R x^2 + x - q = 0.
      const double q = u * u / (R0 * hA);
      const double disc = 1.0 + 4.0 * a * q;
      if (disc < 0.0) {
        s.reason = fmt::format(
            "has no steady temperature: with alpha_R = {:.6g} 1/K < 0 the resistance falls as the "
            "TCA heats and v^2 / R(T) outgrows the losses hA (T - T_amb) (thermal runaway; "
            "1 + 4 alpha_R v^2 / (R0 hA) = {:.6g} < 0)",
            a, disc);
        return s;
      }
      x = 2.0 * q / (1.0 + std::sqrt(disc));
      break;
    }
  }
  s.exists = true;
  s.temperature_K = p.ambient_K + x;
  return s;
}

namespace {

/// Largest Newton iteration count of an implicit step (the laws are smooth and monotone
/// near the solution; a handful of iterations suffices unless the step is refused).
constexpr int kMaxThermalNewton = 50;
/// Smallest accepted g' = 1 - w df/dT of an implicit step (1 for a zero slope; near 0 the
/// step is as long as the runaway growth time 1 / (df/dT) and the solution is meaningless).
constexpr double kMinImplicitPivot = 1e-8;

ThermalStep exact_step(const ThermalParameters& p, ElectricInput input, double u1, double T0,
                       double dt) {
  ThermalStep r;
  const double a = p.resistance_temperature_coefficient_1_K;
  if (input == ElectricInput::kVoltage && a != 0.0) {
    throw DomainError(
        "thermal_step: the exact scheme needs a law linear in T (power or current drive, or "
        "alpha_R = 0); a voltage drive with alpha_R != 0 needs kBackwardEuler or kTrapezoidal");
  }
  // Linear law C dx/dt = b - k C x, x = T - T_amb (k may be <= 0: current-drive runaway).
  double b = 0.0, gain = 0.0;
  switch (input) {
    case ElectricInput::kPower:
      b = u1;
      break;
    case ElectricInput::kCurrent:
      b = u1 * u1 * p.resistance_ohm;
      gain = b * a;
      break;
    case ElectricInput::kVoltage:
      b = u1 * u1 / p.resistance_ohm;
      break;
  }
  const double k = (p.conductance_W_K - gain) / p.heat_capacity_J_K;
  const double x0 = T0 - p.ambient_K;
  // x(dt) = x0 e^{-k dt} + (b / C) dt phi(k dt), phi(z) = (1 - e^{-z}) / z (phi(0) = 1).
  const double z = k * dt;
  const double e = std::exp(-z);
  const double phi = z == 0.0 ? 1.0 : -std::expm1(-z) / z;
  r.temperature_K = p.ambient_K + x0 * e + b / p.heat_capacity_J_K * dt * phi;
  r.dT1_dT0 = e;
  r.converged = std::isfinite(r.temperature_K);
  if (!r.converged) r.message = "thermal_step: the exact step overflowed (thermal runaway)";
  if (r.converged && input == ElectricInput::kCurrent) {
    try {
      (void)p.resistance_ohm_at(r.temperature_K);
    } catch (const DomainError& ex) {
      r.converged = false;
      r.message = ex.what();
    }
  }
  return r;
}

}  // namespace

ThermalStep thermal_step(const ThermalParameters& p, ElectricInput input, double u0, double u1,
                         double T0, double dt, ThermalScheme scheme) {
  if (scheme == ThermalScheme::kExact) return exact_step(p, input, u1, T0, dt);
  ThermalStep r;
  const bool trap = scheme == ThermalScheme::kTrapezoidal;
  const double w = trap ? 0.5 * dt : dt;
  double explicit_part = T0;
  double f0_dT = 0.0;
  try {
    if (trap) {
      const HeatingRate h0 = heating_rate(p, input, u0, T0);
      explicit_part += w * h0.dT_dt_K_s;
      f0_dT = h0.d_dT_1_s;
    }
  } catch (const DomainError& ex) {
    r.message = ex.what();
    return r;
  }
  // g(T1) = T1 - explicit_part - w f(T1, u1) = 0 by Newton, the update halved until R(T1) > 0
  // and |g| decreases (a voltage drive with alpha_R < 0 has a pole where R = 0).
  double T = T0;
  auto g_of = [&](double t, double& dg) {
    const HeatingRate h = heating_rate(p, input, u1, t);
    dg = 1.0 - w * h.d_dT_1_s;
    return t - explicit_part - w * h.dT_dt_K_s;
  };
  double dg = 0.0;
  double g = 0.0;
  try {
    g = g_of(T, dg);
  } catch (const DomainError& ex) {
    r.message = ex.what();
    return r;
  }
  for (int it = 1; it <= kMaxThermalNewton; ++it) {
    r.iterations = it;
    // g' = 1 - w df/dT > 1 for a stable law (df/dT < 0); it falls to 0 only where the
    // temperature runs away (df/dT > 0) on a time scale of the step or shorter.
    if (!(dg > kMinImplicitPivot) || !std::isfinite(dg)) {
      r.message = fmt::format(
          "thermal_step: the implicit equation is singular or folded at T = {} K (1 - dt df/dT "
          "= {:.3g} <= {}): the step dt = {} s is too large for a temperature that runs away "
          "(df/dT = {:.3g} 1/s > 0)",
          T, dg, kMinImplicitPivot, dt, (1.0 - dg) / w);
      return r;
    }
    const double dT = -g / dg;
    double lambda = 1.0;
    double T_new = T, g_new = g, dg_new = dg;
    bool accepted = false;
    for (int half = 0; half < 40; ++half, lambda *= 0.5) {
      T_new = T + lambda * dT;
      try {
        g_new = g_of(T_new, dg_new);
      } catch (const DomainError&) {
        continue;  // R(T) <= 0 there: shorten
      }
      if (std::abs(g_new) < std::abs(g) ||
          lambda * std::abs(dT) <= kThermalStepTolerance * (std::abs(T) + 1.0)) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      r.message = fmt::format(
          "thermal_step: no update of T = {} K reduces the implicit residual {} (dt = {} s)", T, g,
          dt);
      return r;
    }
    const double step = std::abs(T_new - T);
    T = T_new;
    g = g_new;
    dg = dg_new;
    if (step <= kThermalStepTolerance * (std::abs(T) + 1.0)) {
      r.converged = true;
      break;
    }
  }
  if (!r.converged) {
    r.message = fmt::format("thermal_step: Newton did not converge in {} iterations (T = {} K)",
                            kMaxThermalNewton, T);
    return r;
  }
  if (!(dg > kMinImplicitPivot)) {
    r.converged = false;
    r.message = fmt::format(
        "thermal_step: the implicit equation is folded at its solution T = {} K (1 - dt df/dT = "
        "{:.3g}): the step dt = {} s is too large for a temperature that runs away",
        T, dg, dt);
    return r;
  }
  r.temperature_K = T;
  // d/dT0 of g(T1; T0) = 0: dg/dT1 dT1 = (1 + w f'(T0) [trapezoidal]) dT0.
  r.dT1_dT0 = (1.0 + (trap ? w * f0_dT : 0.0)) / dg;
  return r;
}

}  // namespace tcasim::tca
