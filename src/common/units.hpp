#pragma once
/// Unit conversions at the edges of the library. Inside, everything is SI
/// (m, N, Pa, kg, K); non-SI values (degC, mm, g, deg) exist only in file keys and
/// command-line flags with a unit suffix and are converted here.

namespace tcasim::units {

/// 0 degC in kelvin.
inline constexpr double kZeroCelsius_K = 273.15;
/// Standard gravity [m/s^2], used to turn a hanging mass in grams into a force.
inline constexpr double kStandardGravity_m_s2 = 9.80665;
inline constexpr double kPi = 3.14159265358979323846;

inline constexpr double degC_to_K(double t_degC) { return t_degC + kZeroCelsius_K; }
inline constexpr double K_to_degC(double t_K) { return t_K - kZeroCelsius_K; }
inline constexpr double deg_to_rad(double a_deg) { return a_deg * (kPi / 180.0); }
inline constexpr double rad_to_deg(double a_rad) { return a_rad * (180.0 / kPi); }
inline constexpr double mm_to_m(double x_mm) { return x_mm * 1e-3; }
inline constexpr double g_to_kg(double m_g) { return m_g * 1e-3; }

}  // namespace tcasim::units
