// The Newton Jacobian of one time step of the rod dynamics (cosserat/dynamics.hpp) against
// central differences of its residual, on the three-TCA rod in 3-D while it moves (heated by
// temperature ramps of different rates, so velocities, strain rates and the BDF-alpha history
// are all non-zero): every column, and separately the columns of the TCA tension states (one
// per TCA string: at the base and at every interior shooting node).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "rod/loads.hpp"
#include "rod/scenario.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::cosserat::testing {
namespace {

/// Central differences on the scaled unknowns (O(1)) at the default step: truncation and
/// round-off both ~eps^(2/3) ~ 4e-11 relative, amplified by the shooting intervals' growth
/// (four intervals here, o.intervals below) and the residual's scale mix.
constexpr double kJacobianTolerance = 1e-6;
/// A perturbation of the converged unknowns (scaled, so about 1e-3 of each component's scale):
/// the Jacobian is checked away from the solution, where every term of the residual counts.
constexpr double kPerturbation = 1e-3;

/// validation/scenarios/three-tca-3d.json with each TCA heated by a ramp of its own rate from
/// its scenario temperature, and light Kelvin-Voigt damping.
rod::RodModel moving_three_tca_rod() {
  const std::filesystem::path dir =
      std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios";
  std::ifstream in(dir / "three-tca-3d.json");
  nlohmann::json j = nlohmann::json::parse(in);
  const double rise_degC[3] = {30.0, -15.0, 40.0};
  for (int i = 0; i < 3; ++i) {
    nlohmann::json& drive = j["actuators"][i]["drive"];
    const double T0 = drive["temperature_degC"].get<double>();
    drive["temperature_degC"] = {{"t_s", {0.0, 0.2}}, {"values", {T0, T0 + rise_degC[i]}}};
  }
  j["body"]["material"]["viscosity_Pa_s"] = 300.0;
  return rod::parse_scenario(j, dir.string());
}

TEST(RodDynamicsJacobian, NewtonJacobianOfAMovingTcaRodMatchesCentralDifferences) {
  const rod::RodModel m = moving_three_tca_rod();
  DynamicsOptions o;
  o.dt_s = 1e-2;
  o.steps = recommended_steps(m, o);
  o.intervals = 4;  // several interior nodes: their tension columns are checked too
  RodDynamics d(m, o);
  ASSERT_TRUE(d.initialize(rod::Loads::at_time(m, 0.0)).converged());
  for (int k = 1; k <= 6; ++k) {
    const DynamicsSummary s = d.step(rod::Loads::at_time(m, k * o.dt_s));
    ASSERT_TRUE(s.converged()) << "step " << k << ": " << s.message;
  }
  ASSERT_GT(d.kinetic_energy_J(), 0.0);  // moving: the inertia and damping terms count
  const int n_act = 3, n_tca = 3, D = d.state_dimension(), M = d.intervals();
  ASSERT_EQ(D, 24 + n_act + n_tca);
  Eigen::VectorXd u = d.scaled_unknowns();
  ASSERT_EQ(u.size(), 6 + n_tca + (M - 1) * D);
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] += kPerturbation * std::sin(1.0 + 7.0 * i);

  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  ASSERT_TRUE(d.newton_system(u, r, &J));
  const auto residual = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd rx;
    EXPECT_TRUE(d.newton_system(x, rx, nullptr));
    return rx;
  };
  const Eigen::MatrixXd J_fd = test_support::jacobian(residual, u);
  ASSERT_EQ(J.rows(), J_fd.rows());
  ASSERT_EQ(J.cols(), J_fd.cols());
  // The tension columns: T_j at the base (6 + j) and at each interior node (24 + n_act + j).
  std::vector<int> cols;
  for (int j = 0; j < n_tca; ++j) {
    cols.push_back(6 + j);
    for (int k = 1; k < M; ++k) cols.push_back(6 + n_tca + (k - 1) * D + 24 + n_act + j);
  }
  Eigen::MatrixXd Jt(J.rows(), cols.size()), Jt_fd(J.rows(), cols.size());
  for (std::size_t c = 0; c < cols.size(); ++c) {
    Jt.col(c) = J.col(cols[c]);
    Jt_fd.col(c) = J_fd.col(cols[c]);
    ASSERT_GT(Jt_fd.col(c).norm(), 0.0) << "column " << cols[c] << " is empty";
  }
  EXPECT_LE(test_support::worst_column_relative_difference(Jt, Jt_fd), kJacobianTolerance);
  EXPECT_LE(test_support::worst_column_relative_difference(J, J_fd), kJacobianTolerance);
  std::printf("unknowns %d, worst column difference: tension %.2e, all %.2e\n",
              static_cast<int>(u.size()), test_support::worst_column_relative_difference(Jt, Jt_fd),
              test_support::worst_column_relative_difference(J, J_fd));
  // The solver goes on from here (a fresh Jacobian at the next step).
  EXPECT_TRUE(d.step(rod::Loads::at_time(m, 7 * o.dt_s)).converged());
}

}  // namespace
}  // namespace tcasim::cosserat::testing
