// Calibration of TCA material parameters (src/tca/calibration.hpp).
#include "tca/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/units.hpp"
#include "tca/curve.hpp"
#include "test_materials.hpp"

namespace tcasim::tca {
namespace {

using testing::K;
using testing::softening;
using testing::sun2022;
using testing::three_thread;

/// Synthetic curves: loads from pushing (hanging masses) to pulling, 25..160 degC.
std::vector<Measurement> synthetic_data(const Parameters& p, const Material& truth) {
  const Tca tca(p, truth);
  std::vector<Measurement> data;
  for (const double F : {-0.147, -0.0736, 0.05, 0.2, 0.5}) {
    for (double t_degC = 25.0; t_degC <= 160.0; t_degC += 5.0) {
      data.push_back({K(t_degC), F, tca.elongation(F, K(t_degC)).elongation_m});
    }
  }
  return data;
}

const std::vector<FitParameter> kShearAndExpansion = {FitParameter::kShearModulus,
                                                      FitParameter::kExpansion};

TEST(TcaCalibration, ParameterAccessorsSetValueSlopeAndExpansion) {
  const Material m = softening();
  for (const FitParameter p :
       {FitParameter::kYoungsModulus, FitParameter::kYoungsModulusSlope,
        FitParameter::kShearModulus, FitParameter::kShearModulusSlope, FitParameter::kExpansion}) {
    const double v = 1.37 * parameter_value(m, p) + 11.0;
    EXPECT_NEAR(parameter_value(with_parameter(m, p, v), p), v, 1e-12 * std::abs(v))
        << to_string(p);
    EXPECT_EQ(parse_fit_parameter(to_string(p), "--fit"), p);
  }
  // Setting the slope keeps the value at T_ref.
  const Material s = with_parameter(m, FitParameter::kShearModulusSlope, -3e6);
  EXPECT_NEAR(s.shear_modulus_Pa.value(m.reference_temperature_K),
              m.shear_modulus_Pa.value(m.reference_temperature_K), 1e-6);
  // Expansion scale of a ratio polynomial scales (d/d0 - 1).
  const Material e = with_parameter(sun2022(), FitParameter::kExpansion, 2.0);
  const double r0 = sun2022().at(K(120.0)).diameter_ratio, r1 = e.at(K(120.0)).diameter_ratio;
  EXPECT_NEAR(r1 - 1.0, 2.0 * (r0 - 1.0), 1e-14);
  EXPECT_THROW((void)parse_fit_parameter("poisson", "--fit"), InputError);
}

TEST(TcaCalibration, RecoversExactParametersToRoundOff) {
  // Exact synthetic data: LM must return the generating values; 1e-8 relative is the
  // accuracy asked of the calibration (xtol 1e-12 on scaled parameters).
  constexpr double kExactRelTol = 1e-8;
  const Parameters p = three_thread();
  Material truth = with_parameter(sun2022(), FitParameter::kShearModulus, 0.26e9);
  truth = with_parameter(truth, FitParameter::kExpansion, 1.15);
  const auto data = synthetic_data(p, truth);
  const Material start = sun2022();  // G = 0.2218e9, expansion scale 1
  const CalibrationResult r = calibrate(p, start, data, kShearAndExpansion);
  EXPECT_NE(r.status, CalibrationStatus::kFailed) << r.message;
  ASSERT_EQ(r.values.size(), 2u);
  EXPECT_NEAR(r.values[0], 0.26e9, kExactRelTol * 0.26e9);
  EXPECT_NEAR(r.values[1], 1.15, kExactRelTol * 1.15);
  EXPECT_LT(r.rms_residual_m, 1e-12);
  EXPECT_GT(r.iterations, 0);
  // The fitted material reproduces the data.
  const Tca fitted(p, r.material);
  EXPECT_NEAR(fitted.elongation(-0.0736, K(140.0)).elongation_m,
              Tca(p, truth).elongation(-0.0736, K(140.0)).elongation_m, 1e-10);
}

TEST(TcaCalibration, RecoversThreeParametersIncludingWeakYoungsModulus) {
  // E_T enters f11 only through sin^2(alpha) terms (~2 % of f11 here), so it is weakly
  // identified; exact data still pin it down.
  constexpr double kExactRelTol = 1e-6;
  const Parameters p = three_thread();
  Material truth = with_parameter(softening(), FitParameter::kYoungsModulus, 1.8e9);
  truth = with_parameter(truth, FitParameter::kShearModulus, 0.38e9);
  const auto data = synthetic_data(p, truth);
  const CalibrationResult r = calibrate(
      p, softening(), data,
      {FitParameter::kYoungsModulus, FitParameter::kShearModulus, FitParameter::kExpansion});
  EXPECT_NE(r.status, CalibrationStatus::kFailed) << r.message;
  EXPECT_NEAR(r.values[0], 1.8e9, kExactRelTol * 1.8e9);
  EXPECT_NEAR(r.values[1], 0.38e9, kExactRelTol * 0.38e9);
  EXPECT_NEAR(r.values[2], 6e-4, kExactRelTol * 6e-4);
}

TEST(TcaCalibration, NoisyDataGiveEstimatesWithinThreeStandardErrors) {
  const Parameters p = three_thread();
  Material truth = with_parameter(sun2022(), FitParameter::kShearModulus, 0.24e9);
  truth = with_parameter(truth, FitParameter::kExpansion, 0.9);
  auto data = synthetic_data(p, truth);
  const double sigma_m = 0.2e-3;  // laser sensor noise level
  std::mt19937 rng(20190101);     // fixed seed: the test is deterministic
  std::normal_distribution<double> noise(0.0, sigma_m);
  for (Measurement& m : data) m.elongation_m += noise(rng);
  const CalibrationResult r = calibrate(p, sun2022(), data, kShearAndExpansion);
  EXPECT_NE(r.status, CalibrationStatus::kFailed) << r.message;
  std::printf(
      "noisy fit (%s, %d iterations): G = %.6g +- %.3g Pa, expansion = %.6g +- %.3g, "
      "rms %.3g m\n",
      to_string(r.status), r.iterations, r.values[0], r.standard_errors[0], r.values[1],
      r.standard_errors[1], r.rms_residual_m);
  const double truth_values[] = {0.24e9, 0.9};
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_TRUE(std::isfinite(r.standard_errors[i]));
    EXPECT_GT(r.standard_errors[i], 0.0);
    EXPECT_LT(std::abs(r.values[i] - truth_values[i]), 3.0 * r.standard_errors[i])
        << to_string(r.parameters[i]) << " = " << r.values[i] << " +- " << r.standard_errors[i];
  }
  // The residual is the noise: its RMS is sigma to within sampling (140 points, ~10 %).
  EXPECT_NEAR(r.rms_residual_m, sigma_m, 0.25 * sigma_m);
}

TEST(TcaCalibration, ReadsCsvWithLoadInGrams) {
  const std::string path = ::testing::TempDir() + "tca_calibration_test.csv";
  {
    std::ofstream out(path);
    out << "# measured\ntemperature_degC,load_g,elongation_m,comment\n"
        << "25,7.5,0.0,first\n100, 15 ,0.0125,x\n";
  }
  const auto data = read_measurements_csv(path);
  ASSERT_EQ(data.size(), 2u);
  EXPECT_DOUBLE_EQ(data[1].temperature_K, K(100.0));
  EXPECT_DOUBLE_EQ(data[1].tension_N, -0.015 * units::kStandardGravity_m_s2);
  EXPECT_DOUBLE_EQ(data[1].elongation_m, 0.0125);
  {
    std::ofstream out(path);
    out << "temperature_degC,tension_N,elongation_m\n25,abc,0\n";
  }
  try {
    (void)read_measurements_csv(path);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":2 column tension_N = abc"), std::string::npos)
        << e.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW((void)read_measurements_csv(path), InputError);
}

}  // namespace
}  // namespace tcasim::tca
