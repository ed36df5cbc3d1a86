#include "tca/calibration.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <unsupported/Eigen/LevenbergMarquardt>

#include "common/error.hpp"
#include "common/units.hpp"
#include "tca/curve.hpp"

namespace tcasim::tca {
namespace {

/// Residual [m] given to a point whose model evaluation fails (parameters outside the
/// model's domain): large against any TCA elongation, so LM rejects the step.
constexpr double kFailedResidual_m = 10.0;

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? std::string() : cell.substr(b, e - b + 1));
  }
  return cells;
}

double evaluate_polynomial_degC(const std::vector<double>& c, double t_degC) {
  double v = 0.0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) v = v * t_degC + *it;
  return v;
}

/// Typical magnitude used to scale a parameter for the solver.
double parameter_scale(const Material& m, FitParameter p, double value) {
  if (value != 0.0) return std::abs(value);
  switch (p) {
    case FitParameter::kYoungsModulusSlope:
      return 1e-3 * std::abs(m.youngs_modulus_Pa.value(m.reference_temperature_K));
    case FitParameter::kShearModulusSlope:
      return 1e-3 * std::abs(m.shear_modulus_Pa.value(m.reference_temperature_K));
    case FitParameter::kExpansion:
      return 1e-4;  // 1/K, a typical polymer expansion coefficient
    default:
      return 1.0;
  }
}

/// Least-squares problem in scaled parameters x_i = value_i / scale_i.
struct Problem : Eigen::DenseFunctor<double> {
  const Parameters& geometry;
  const Material& initial;
  const std::vector<Measurement>& data;
  const std::vector<FitParameter>& fit;
  std::vector<double> scale;
  double step;
  std::string last_error;

  Problem(const Parameters& g, const Material& m, const std::vector<Measurement>& d,
          const std::vector<FitParameter>& f, std::vector<double> s, double h)
      : Eigen::DenseFunctor<double>(static_cast<int>(f.size()), static_cast<int>(d.size())),
        geometry(g),
        initial(m),
        data(d),
        fit(f),
        scale(std::move(s)),
        step(h) {}

  Material material(const Eigen::VectorXd& x) const {
    Material m = initial;
    for (std::size_t i = 0; i < fit.size(); ++i) {
      m = with_parameter(m, fit[i], x[static_cast<Eigen::Index>(i)] * scale[i]);
    }
    return m;
  }

  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(static_cast<Eigen::Index>(data.size()));
    try {
      const Tca tca(geometry, material(x));
      for (std::size_t j = 0; j < data.size(); ++j) {
        const auto idx = static_cast<Eigen::Index>(j);
        try {
          r[idx] = tca.elongation(data[j].tension_N, data[j].temperature_K).elongation_m -
                   data[j].elongation_m;
        } catch (const DomainError& e) {
          last_error = e.what();
          r[idx] = kFailedResidual_m;
        }
      }
    } catch (const std::exception& e) {  // invalid material for these parameters
      last_error = e.what();
      r.setConstant(kFailedResidual_m);
    }
    return 0;
  }

  /// Central differences in scaled parameters.
  int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jac) {
    jac.resize(values(), inputs());
    Eigen::VectorXd xp = x, rp, rm;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double h = step * std::max(1.0, std::abs(x[i]));
      xp[i] = x[i] + h;
      (*this)(xp, rp);
      xp[i] = x[i] - h;
      (*this)(xp, rm);
      xp[i] = x[i];
      jac.col(i) = (rp - rm) / (2.0 * h);
    }
    return 0;
  }
};

}  // namespace

std::vector<Measurement> read_measurements_csv(const std::string& path) {
  std::ifstream in(path);
  require(static_cast<bool>(in), "--data", path, "cannot be opened");
  std::string line;
  int line_no = 0;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    header = split_csv_line(line);
    break;
  }
  const auto column = [&](const std::string& name) -> int {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : static_cast<int>(it - header.begin());
  };
  const int c_t = column("temperature_degC"), c_e = column("elongation_m");
  const int c_f = column("tension_N"), c_m = column("load_g");
  require(c_t >= 0 && c_e >= 0 && (c_f >= 0) != (c_m >= 0), path + ": header", line,
          "must name temperature_degC, elongation_m and exactly one of tension_N, load_g");
  std::vector<Measurement> data;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const auto cells = split_csv_line(line);
    const auto number = [&](int c, const char* name) {
      const std::string key = fmt::format("{}:{} column {}", path, line_no, name);
      require(c < static_cast<int>(cells.size()), key, "(missing)", "must be a number");
      const std::string& s = cells[static_cast<std::size_t>(c)];
      char* end = nullptr;
      const double v = std::strtod(s.c_str(), &end);
      require(!s.empty() && end == s.c_str() + s.size() && std::isfinite(v), key, s,
              "must be a finite number");
      return v;
    };
    Measurement m{};
    const double t_degC = number(c_t, "temperature_degC");
    require(t_degC > -units::kZeroCelsius_K,
            fmt::format("{}:{} column temperature_degC", path, line_no), t_degC,
            "is below absolute zero");
    m.temperature_K = units::degC_to_K(t_degC);
    m.elongation_m = number(c_e, "elongation_m");
    m.tension_N = c_f >= 0 ? number(c_f, "tension_N")
                           : hanging_load_tension_N(units::g_to_kg(number(c_m, "load_g")));
    data.push_back(m);
  }
  require(!data.empty(), "--data", path, "has no data rows");
  return data;
}

const char* to_string(FitParameter p) {
  switch (p) {
    case FitParameter::kYoungsModulus:
      return "youngs_modulus";
    case FitParameter::kYoungsModulusSlope:
      return "youngs_modulus_slope";
    case FitParameter::kShearModulus:
      return "shear_modulus";
    case FitParameter::kShearModulusSlope:
      return "shear_modulus_slope";
    case FitParameter::kExpansion:
      return "expansion";
  }
  return "?";
}

FitParameter parse_fit_parameter(const std::string& name, const std::string& key) {
  for (const FitParameter p :
       {FitParameter::kYoungsModulus, FitParameter::kYoungsModulusSlope,
        FitParameter::kShearModulus, FitParameter::kShearModulusSlope, FitParameter::kExpansion}) {
    if (name == to_string(p)) return p;
  }
  throw InputError(key, name,
                   "must be one of youngs_modulus, youngs_modulus_slope, shear_modulus, "
                   "shear_modulus_slope, expansion");
}

const char* to_string(CalibrationStatus s) {
  switch (s) {
    case CalibrationStatus::kConverged:
      return "converged";
    case CalibrationStatus::kMaxEvaluations:
      return "max_evaluations";
    case CalibrationStatus::kToleranceTooSmall:
      return "tolerance_too_small";
    case CalibrationStatus::kFailed:
      return "failed";
  }
  return "?";
}

double parameter_value(const Material& m, FitParameter p) {
  const double t = m.reference_temperature_K;
  switch (p) {
    case FitParameter::kYoungsModulus:
      return m.youngs_modulus_Pa.value(t);
    case FitParameter::kYoungsModulusSlope:
      return m.youngs_modulus_Pa.derivative(t);
    case FitParameter::kShearModulus:
      return m.shear_modulus_Pa.value(t);
    case FitParameter::kShearModulusSlope:
      return m.shear_modulus_Pa.derivative(t);
    case FitParameter::kExpansion:
      return m.diameter.type == DiameterLaw::Type::kLinearExpansion
                 ? m.diameter.linear_expansion_1_K
                 : 1.0;
  }
  return 0.0;
}

Material with_parameter(const Material& m, FitParameter p, double value) {
  Material out = m;
  const double t_ref_degC = units::K_to_degC(m.reference_temperature_K);
  const auto shift_value = [&](PolynomialDegC& poly) {
    if (poly.coefficients.empty()) poly.coefficients.push_back(0.0);
    poly.coefficients[0] += value - poly.value(m.reference_temperature_K);
  };
  const auto shift_slope = [&](PolynomialDegC& poly) {
    if (poly.coefficients.size() < 2) poly.coefficients.resize(2, 0.0);
    // Add (value - slope) (T - T_ref): the value at T_ref is kept.
    const double ds = value - poly.derivative(m.reference_temperature_K);
    poly.coefficients[1] += ds;
    poly.coefficients[0] -= ds * t_ref_degC;
  };
  switch (p) {
    case FitParameter::kYoungsModulus:
      shift_value(out.youngs_modulus_Pa);
      break;
    case FitParameter::kYoungsModulusSlope:
      shift_slope(out.youngs_modulus_Pa);
      break;
    case FitParameter::kShearModulus:
      shift_value(out.shear_modulus_Pa);
      break;
    case FitParameter::kShearModulusSlope:
      shift_slope(out.shear_modulus_Pa);
      break;
    case FitParameter::kExpansion:
      if (out.diameter.type == DiameterLaw::Type::kLinearExpansion) {
        out.diameter.linear_expansion_1_K = value;
      } else {
        // p'(T) = p_ref + s (p(T) - p_ref): d/d0 = p'/p'_ref = 1 + s (p/p_ref - 1).
        auto& c = out.diameter.ratio_polynomial.coefficients;
        const double p_ref = evaluate_polynomial_degC(c, t_ref_degC);
        for (double& ci : c) ci *= value;
        if (c.empty()) c.push_back(0.0);
        c[0] += p_ref * (1.0 - value);
      }
      break;
  }
  return out;
}

CalibrationResult calibrate(const Parameters& parameters, const Material& initial,
                            const std::vector<Measurement>& data,
                            const std::vector<FitParameter>& fit,
                            const CalibrationOptions& options) {
  require(!fit.empty(), "fit", "[]", "must name at least one parameter");
  require(!data.empty(), "data", "[]", "must hold at least one measurement");
  for (std::size_t i = 0; i < fit.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      require(fit[i] != fit[j], "fit", to_string(fit[i]), "is listed twice");
    }
  }
  (void)Tca(parameters, initial);  // validates geometry and the initial material

  CalibrationResult result;
  result.parameters = fit;
  std::vector<double> scale;
  Eigen::VectorXd x(static_cast<Eigen::Index>(fit.size()));
  for (std::size_t i = 0; i < fit.size(); ++i) {
    const double v = parameter_value(initial, fit[i]);
    result.initial_values.push_back(v);
    scale.push_back(parameter_scale(initial, fit[i], v));
    x[static_cast<Eigen::Index>(i)] = v / scale.back();
  }
  Problem problem(parameters, initial, data, fit, scale, options.jacobian_step);
  Eigen::LevenbergMarquardt<Problem> lm(problem);
  lm.setXtol(options.xtol);
  lm.setFtol(options.ftol);
  lm.setGtol(options.gtol);
  lm.setMaxfev(options.max_function_evaluations);
  const auto status = lm.minimize(x);
  namespace S = Eigen::LevenbergMarquardtSpace;
  switch (status) {
    case S::RelativeReductionTooSmall:
    case S::RelativeErrorTooSmall:
    case S::RelativeErrorAndReductionTooSmall:
    case S::CosinusTooSmall:
      result.status = CalibrationStatus::kConverged;
      break;
    case S::TooManyFunctionEvaluation:
      result.status = CalibrationStatus::kMaxEvaluations;
      break;
    case S::FtolTooSmall:
    case S::XtolTooSmall:
    case S::GtolTooSmall:
      result.status = CalibrationStatus::kToleranceTooSmall;
      break;
    default:
      result.status = CalibrationStatus::kFailed;
      break;
  }
  result.message = fmt::format("Eigen LevenbergMarquardt status {}", static_cast<int>(status));
  if (!problem.last_error.empty()) {
    result.message += "; last model evaluation error: " + problem.last_error;
  }
  result.iterations = static_cast<int>(lm.iterations());
  result.function_evaluations = static_cast<int>(lm.nfev());

  // Residuals and covariance at the optimum: cov = s^2 (J^T J)^-1, s^2 = SSR/(m - p).
  // Computed in the scaled parameters (columns of similar size, so the rank test of the
  // LU is meaningful) and scaled back: se_i = scale_i sqrt(cov_scaled_ii).
  Eigen::VectorXd r;
  problem(x, r);
  Eigen::MatrixXd jac;
  problem.df(x, jac);
  const double ssr = r.squaredNorm();
  const auto m = static_cast<double>(data.size()), p = static_cast<double>(fit.size());
  result.rms_residual_m = std::sqrt(ssr / m);
  result.material = problem.material(x);
  const Eigen::MatrixXd jtj = jac.transpose() * jac;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(jtj);
  const bool identifiable = m > p && lu.isInvertible();
  const Eigen::MatrixXd cov =
      identifiable ? Eigen::MatrixXd(lu.inverse() * (ssr / (m - p))) : Eigen::MatrixXd();
  for (std::size_t i = 0; i < fit.size(); ++i) {
    const auto idx = static_cast<Eigen::Index>(i);
    result.values.push_back(x[idx] * scale[i]);
    result.standard_errors.push_back(identifiable ? scale[i] * std::sqrt(cov(idx, idx))
                                                  : std::numeric_limits<double>::quiet_NaN());
  }
  return result;
}

}  // namespace tcasim::tca
