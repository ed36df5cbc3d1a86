#pragma once
/// Calibration of TCA material parameters to measured elongation curves by nonlinear
/// least squares (Eigen's Levenberg-Marquardt). The model is the elongation law of
/// Tca::elongation (Eqs. (1)-(5), closed coils included); residuals are elongations [m].
#include <string>
#include <vector>

#include "tca/tca.hpp"

namespace tcasim::tca {

/// One measured point.
struct Measurement {
  double temperature_K;
  double tension_N;     ///< applied tension (a hanging mass m gives -m g)
  double elongation_m;  ///< measured delta
};

/// Reads a CSV with a header naming `temperature_degC`, `elongation_m` and either
/// `tension_N` or `load_g` (hanging mass in grams, F = -m g). Other columns are ignored.
/// Throws InputError naming the file, line and column on malformed input.
std::vector<Measurement> read_measurements_csv(const std::string& path);

/// A material parameter that can be fitted. Each is defined so that any polynomial law
/// can be adjusted: the value/slope at the reference temperature T_ref is changed by adding
/// a constant / a linear term in (T - T_ref), the rest of the polynomial is kept.
enum class FitParameter {
  kYoungsModulus,       ///< E_T(T_ref) [Pa]           ("youngs_modulus")
  kYoungsModulusSlope,  ///< dE_T/dT at T_ref [Pa/K]   ("youngs_modulus_slope")
  kShearModulus,        ///< G_T(T_ref) [Pa]           ("shear_modulus")
  kShearModulusSlope,   ///< dG_T/dT at T_ref [Pa/K]   ("shear_modulus_slope")
  /// Diameter expansion: rho [1/K] for a linear law; for a ratio polynomial the scale s in
  /// d/d0 = 1 + s (p(T)/p(T_ref) - 1), 1 for the material as given ("expansion").
  kExpansion,
};

/// CLI/file name of a parameter.
const char* to_string(FitParameter p);
/// Parses a name listed in FitParameter; throws InputError(key, name, rule) otherwise.
FitParameter parse_fit_parameter(const std::string& name, const std::string& key);

/// Current value of a parameter of `m` (kExpansion of a ratio polynomial: 1).
double parameter_value(const Material& m, FitParameter p);
/// Copy of `m` with parameter p set to `value`.
Material with_parameter(const Material& m, FitParameter p, double value);

/// Solver settings (Eigen LevenbergMarquardt tolerances, on scaled parameters).
struct CalibrationOptions {
  double xtol = 1e-12;  ///< relative step tolerance
  double ftol = 1e-14;  ///< relative reduction tolerance of the sum of squares
  double gtol = 0.0;    ///< orthogonality tolerance (off)
  int max_function_evaluations = 4000;
  /// Central-difference step in scaled parameters (parameter / its initial magnitude).
  double jacobian_step = 1e-6;
};

/// Outcome of a calibration.
enum class CalibrationStatus {
  kConverged,          ///< a relative reduction, step or error test of MINPACK was met
  kMaxEvaluations,     ///< max_function_evaluations reached
  kToleranceTooSmall,  ///< ftol/xtol/gtol too small for further progress (usually at optimum)
  kFailed,             ///< improper input or a model evaluation failed
};
const char* to_string(CalibrationStatus s);

/// Fitted values with their uncertainty.
struct CalibrationResult {
  Material material;                     ///< the material with the fitted values
  std::vector<FitParameter> parameters;  ///< in the order requested
  std::vector<double> initial_values;
  std::vector<double> values;
  /// sqrt(diag((J^T J)^-1) s^2) with s^2 = SSR/(m - p); NaN if m <= p or J^T J singular.
  std::vector<double> standard_errors;
  double rms_residual_m = 0.0;  ///< sqrt(SSR/m)
  int iterations = 0;
  int function_evaluations = 0;
  CalibrationStatus status = CalibrationStatus::kFailed;
  std::string message;  ///< Eigen's status and any evaluation error
};

/// Fits `fit` of `initial` to the measurements with the TCA geometry `parameters`.
/// Throws InputError if nothing is fitted, a parameter is repeated or data are empty.
CalibrationResult calibrate(const Parameters& parameters, const Material& initial,
                            const std::vector<Measurement>& data,
                            const std::vector<FitParameter>& fit,
                            const CalibrationOptions& options = {});

}  // namespace tcasim::tca
