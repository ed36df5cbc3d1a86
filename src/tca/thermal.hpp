#pragma once
/// Lumped electro-thermal model of a TCA (docs/conventions.md "Electro-thermal TCA"):
///
///   C dT/dt = P(T) - hA (T - T_amb),   R(T) = R0 (1 + alpha_R (T - T_amb)),
///   P = i^2 R(T) (current drive), v^2 / R(T) (voltage drive) or p (power drive).
///
/// [Yip2017], [Sun2022]. One set of parameters describes a whole TCA; a segment of length
/// fraction f takes f C, f hA and f R0 (ThermalParameters::fraction). Temperatures in K,
/// SI otherwise.
#include <string>

namespace tcasim::tca {

/// The lumped parameters of a TCA (or of one segment of it).
struct ThermalParameters {
  double heat_capacity_J_K = 0.0;  ///< C = m c_p [J/K]
  double conductance_W_K = 0.0;    ///< hA, heat loss per kelvin above ambient [W/K]
  double ambient_K = 0.0;          ///< T_amb [K]
  double resistance_ohm = 0.0;     ///< R0, electrical resistance at T_amb [ohm]
  double resistance_temperature_coefficient_1_K = 0.0;  ///< alpha_R [1/K]

  /// The parameters of a segment with length fraction f in (0, 1]: C, hA and R0 times f.
  ThermalParameters fraction(double f) const;
  /// Thermal time constant C / hA [s] (of the linear law: alpha_R = 0 or a power drive).
  double time_constant_s() const { return heat_capacity_J_K / conductance_W_K; }
  /// R(T) [ohm]; throws DomainError if it is not positive at T_K.
  double resistance_ohm_at(double T_K) const;
};

/// What the electric drive prescribes.
enum class ElectricInput { kVoltage, kCurrent, kPower };

/// Key name of an input in scenario files: "voltage_V", "current_A", "power_W".
const char* key_name(ElectricInput input);

/// Joule power and its temperature derivative.
struct JoulePower {
  double power_W = 0.0;    ///< P(T)
  double dP_dT_W_K = 0.0;  ///< dP/dT
};
/// P(T) for drive value u (V, A or W) [W]; DomainError if R(T) <= 0 for a voltage or current
/// drive.
JoulePower joule_power(const ThermalParameters& p, ElectricInput input, double u, double T_K);

/// Right-hand side f(T) = (P(T) - hA (T - T_amb)) / C [K/s] and df/dT [1/s], for an implicit
/// integrator.
struct HeatingRate {
  double dT_dt_K_s = 0.0;
  double d_dT_1_s = 0.0;
};
HeatingRate heating_rate(const ThermalParameters& p, ElectricInput input, double u, double T_K);

/// The steady temperature P(T) = hA (T - T_amb) reached from T_amb under a constant drive u.
/// Closed forms (x = T - T_amb, q = u^2 / (R0 hA)):
///  - power:   x = p / hA;
///  - current: x = i^2 R0 / (hA - i^2 R0 alpha_R); none if i^2 R0 alpha_R >= hA (thermal
///             runaway: the Joule power grows faster with T than the losses);
///  - voltage: alpha_R hA x^2 + hA x - v^2 / R0 = 0, the root reached from ambient
///             x = 2 q / (1 + sqrt(1 + 4 alpha_R q)) (no cancellation); none if
///             1 + 4 alpha_R q < 0 (alpha_R < 0: runaway).
struct SteadyTemperature {
  bool exists = false;
  double temperature_K = 0.0;  ///< valid when exists
  std::string reason;          ///< why none exists (empty when exists)
};
SteadyTemperature steady_temperature(const ThermalParameters& p, ElectricInput input, double u);

/// Time steppers for T over one step dt with the drive u0 just after t_n (the right limit
/// at a jump) and u1 at t_{n+1}.
enum class ThermalScheme {
  kBackwardEuler,  ///< T1 = T0 + dt f(T1, u1): first order, L-stable
  kTrapezoidal,    ///< T1 = T0 + dt/2 (f(T0, u0) + f(T1, u1)): second order, A-stable
  kExact,  ///< exact for a law linear in T (power drive, current drive, or alpha_R = 0) with
           ///< the input held at u1 over the step (exact for piecewise-constant inputs
           ///< stepped onto their breakpoints); DomainError for a voltage drive with alpha_R != 0
};

/// Outcome of one step.
struct ThermalStep {
  bool converged = false;  ///< Newton met |dT| <= kThermalStepTolerance (|T| + 1)
  double temperature_K = 0.0;
  double dT1_dT0 = 0.0;  ///< sensitivity of T1 to T0 (for a monolithic Newton around it)
  int iterations = 0;
  std::string message;  ///< why it failed (empty when converged)
};
/// Relative Newton tolerance on the temperature update of the implicit steps.
inline constexpr double kThermalStepTolerance = 1e-13;
ThermalStep thermal_step(const ThermalParameters& p, ElectricInput input, double u0, double u1,
                         double T0_K, double dt_s, ThermalScheme scheme);

}  // namespace tcasim::tca
