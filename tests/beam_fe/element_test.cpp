// Element and assembled tangents against central differences of the residual, and the
// dual-number rotation formulas against src/common/so3.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "beam_fe/beam_fe.hpp"
#include "common/dual.hpp"
#include "common/lie_series.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "models.hpp"
#include "support/finite_difference.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// Central differences with h ~ eps^(1/3) are accurate to ~1e-10 relative on O(1) entries;
/// 1e-7 of the scaled tangent leaves margin for the curvature of the residual.
constexpr double kTangentTolerance = 1e-7;
/// Dual-number formulas vs so3: the same closed forms, round-off only.
constexpr double kRoundOff = 1e-13;
/// Position increments of eps^(1/3) m are 1.5e-4 of a 13 mm element (strain changes of
/// that size give a truncation error ~1e-7); 1e-7 m keeps truncation and round-off ~1e-9.
constexpr double kMillimetreScaleStep = 1e-7;

/// max_ij |A_ij - B_ij| / sqrt(row_i col_j), with row/col the largest |B| in that row/column
/// (a symmetric diagonal scaling, so small moment rows are checked as strictly as force rows).
double scaled_difference(const MatrixXd& A, const MatrixXd& B) {
  const VectorXd row = B.cwiseAbs().rowwise().maxCoeff().cwiseMax(1e-300);
  const VectorXd col = B.cwiseAbs().colwise().maxCoeff().transpose().cwiseMax(1e-300);
  double worst = 0.0;
  for (int i = 0; i < A.rows(); ++i)
    for (int j = 0; j < A.cols(); ++j)
      worst = std::max(worst, std::abs(A(i, j) - B(i, j)) / std::sqrt(row[i] * col[j]));
  return worst;
}

/// A dimensionless rod (L = 1) with anisotropic stiffness, a precurved reference, one
/// straight and one helical tension string.
rod::RodModel test_rod() {
  rod::RodModel m = testing::stiffness_rod(1.0, 3.0, 2.0, 0.5, 0.7, 0.4);
  m.set_reference_curvature({0.3, -0.2, 0.1});
  testing::add_tension_string(m, "straight", 0.1, -0.05, 0.2, 2);
  testing::add_tension_string(m, "helix", 0.08, 0.0, 0.15, 1, 0.7);
  return m;
}

/// The reference state moved by a random increment of every free node.
State perturbed_state(const Discretization& disc, unsigned seed, double size) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-size, size);
  State st = disc.reference_state();
  VectorXd dx(disc.dof_count());
  for (int i = 0; i < dx.size(); ++i) dx[i] = u(gen);
  disc.retract(st, dx);
  return st;
}

/// Moves the nodes of element e by local increments (dp_a, dtheta_a).
State move_element(const State& st, int e, int order, const VectorXd& eta) {
  State out = st;
  for (int a = 0; a <= order; ++a) {
    const int k = e * order + a;
    out.p_W_m[k] += eta.segment<3>(6 * a);
    out.q_WB[k] = (out.q_WB[k] * so3::exp_quaternion(eta.segment<3>(6 * a + 3))).normalized();
  }
  return out;
}

void check_element(int order, Integration integration) {
  const rod::RodModel model = test_rod();
  Options opt;
  opt.elements = 3;
  opt.order = order;
  opt.integration = integration;
  const Discretization disc(model, opt);
  const State st = perturbed_state(disc, 7u + static_cast<unsigned>(order), 0.3);
  const std::vector<double> tensions{0.2, -0.15};
  for (int e = 0; e < disc.element_count(); ++e) {
    SCOPED_TRACE("element " + std::to_string(e));
    const ElementEvaluation ev = disc.element(st, e, tensions);
    const VectorXd zero = VectorXd::Zero(6 * (order + 1));
    const MatrixXd K_fd = test_support::jacobian(
        [&](const VectorXd& eta) {
          return disc.element(move_element(st, e, order, eta), e, tensions).residual;
        },
        zero);
    EXPECT_LT(scaled_difference(ev.tangent, K_fd), kTangentTolerance);
    for (std::size_t i = 0; i < tensions.size(); ++i) {
      const VectorXd g_fd = test_support::gradient(
          [&](const VectorXd& eta) {
            return disc.element(move_element(st, e, order, eta), e, tensions).lengths_m[i];
          },
          zero);
      EXPECT_LT((ev.length_gradients[i] - g_fd).lpNorm<Eigen::Infinity>(),
                kTangentTolerance * ev.length_gradients[i].lpNorm<Eigen::Infinity>());
    }
  }
}

TEST(BeamFeElement, LinearReducedTangentMatchesFiniteDifferences) {
  check_element(1, Integration::kReduced);
}
TEST(BeamFeElement, LinearFullTangentMatchesFiniteDifferences) {
  check_element(1, Integration::kFull);
}
TEST(BeamFeElement, QuadraticReducedTangentMatchesFiniteDifferences) {
  check_element(2, Integration::kReduced);
}
TEST(BeamFeElement, QuadraticFullTangentMatchesFiniteDifferences) {
  check_element(2, Integration::kFull);
}

TEST(BeamFeElement, ResidualIsTheGradientOfTheElementEnergyAtZeroTensionsAndRotationsNearZero) {
  // Nodal rotations below the series threshold of the dual-number coefficients exercise
  // that branch in the tangent.
  const rod::RodModel model = test_rod();
  Options opt;
  opt.elements = 40;
  opt.order = 2;
  const Discretization disc(model, opt);
  const State st = perturbed_state(disc, 3u, 1e-3);
  const std::vector<double> tensions{0.2, -0.15};
  const ElementEvaluation ev = disc.element(st, 5, tensions);
  const MatrixXd K_fd = test_support::jacobian(
      [&](const VectorXd& eta) {
        return disc.element(move_element(st, 5, 2, eta), 5, tensions).residual;
      },
      VectorXd::Zero(18));
  EXPECT_LT(scaled_difference(ev.tangent, K_fd), kTangentTolerance);
}

TEST(BeamFeAssembly, BorderedTangentWithTcaTipMomentAndGravityMatchesFiniteDifferences) {
  rod::RodModel model = testing::circular_manipulator(units::degC_to_K(90.0));
  testing::add_tension_string(model, "helix", 0.002, 0.001, 0.004, 1, 20.0);
  model.tip_moment_W_Nm = {2e-5, -1e-5, 3e-6};
  model.tip_force_W_N = {1e-3, 0.0, -2e-3};
  Options opt;
  opt.elements = 3;
  opt.order = 2;
  const Discretization disc(model, opt);
  const LoadCase disc_loads = disc.load_case(rod::Loads::from_model(model));
  State st = perturbed_state(disc, 11u, 0.002);
  st.tensions_N = {-0.02, 0.004};
  const double lambda = 0.7;
  disc.apply_prescribed_tensions(disc_loads, st, lambda);
  Eigen::SparseMatrix<double> K;
  disc.residual(st, disc_loads, lambda, &K);
  const MatrixXd K_fd = test_support::jacobian(
      [&](const VectorXd& dx) {
        State t = st;
        disc.retract(t, dx);
        return disc.residual(t, disc_loads, lambda);
      },
      VectorXd::Zero(disc.dof_count()), kMillimetreScaleStep);
  EXPECT_LT(scaled_difference(MatrixXd(K), K_fd), kTangentTolerance);
}

TEST(BeamFeAssembly, BorderedTangentWithPinnedOrNormalTipConstraintMatchesFiniteDifferences) {
  for (const bool normal_only : {false, true}) {
    SCOPED_TRACE(normal_only ? "normal-only" : "pinned");
    rod::RodModel model = testing::circular_manipulator(units::degC_to_K(90.0));
    model.tip_moment_W_Nm = {2e-5, -1e-5, 3e-6};
    rod::TipConstraint c;
    c.position_W_m = {-0.004, 0.001, 0.037};
    if (normal_only) c.normal_W = Vector3d(0.8, -0.36, 0.48);
    model.tip_constraint = c;
    Options opt;
    opt.elements = 3;
    opt.order = 2;
    const Discretization disc(model, opt);
    const LoadCase disc_loads = disc.load_case(rod::Loads::from_model(model));
    ASSERT_EQ(disc.constraint_count(), normal_only ? 1 : 3);
    State st = perturbed_state(disc, 13u, 0.002);
    st.tensions_N = {-0.02};
    st.tip_reaction_W_N =
        normal_only ? Vector3d(0.012 * *c.normal_W) : Vector3d(0.01, -0.02, 0.005);
    const double lambda = 0.6;
    Eigen::SparseMatrix<double> K;
    const VectorXd r = disc.residual(st, disc_loads, lambda, &K);
    // The constraint rows are not trivially zero here (the tip is off its target).
    EXPECT_GT(r.tail(disc.constraint_count()).cwiseAbs().maxCoeff(), 1e-6);
    const MatrixXd K_fd = test_support::jacobian(
        [&](const VectorXd& dx) {
          State t = st;
          disc.retract(t, dx);
          return disc.residual(t, disc_loads, lambda);
        },
        VectorXd::Zero(disc.dof_count()), kMillimetreScaleStep);
    EXPECT_LT(scaled_difference(MatrixXd(K), K_fd), kTangentTolerance);
  }
}

/// alpha I + beta K + gamma K^2 (K = hat(phi), row-major 3x3) over dual scalars, from the
/// shared coefficients: the rotation formulas whose derivatives the element kernel uses.
template <class S>
using Row3x3 = std::array<S, 9>;
template <class S>
Row3x3<S> combine(const S& alpha, const S& beta, const S& gamma, const std::array<S, 3>& phi) {
  const S K[9] = {S(0.0), -phi[2], phi[1], phi[2], S(0.0), -phi[0], -phi[1], phi[0], S(0.0)};
  Row3x3<S> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[3 * i + j] = beta * K[3 * i + j] +
                     gamma * (K[3 * i] * K[j] + K[3 * i + 1] * K[3 + j] + K[3 * i + 2] * K[6 + j]) +
                     (i == j ? alpha : S(0.0));
  return r;
}

TEST(BeamFeDual, RotationFormulasMatchSo3AndTheirDerivativesMatchFiniteDifferences) {
  using D3 = ad::Dual<double, 3>;
  for (const double angle : {0.0, 1e-6, 0.05, 0.0999, 0.1001, 1.0, 3.0}) {
    SCOPED_TRACE("angle " + std::to_string(angle));
    const Vector3d phi = angle * Vector3d(0.3, -0.5, 0.8).normalized();
    std::array<D3, 3> p;
    for (int k = 0; k < 3; ++k) {
      p[k] = D3(phi[k]);
      p[k].d[k] = 1.0;
    }
    const so3::Coefficients<D3> c = so3::coefficients(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const auto E = combine(D3(1.0), c.a, c.b, p);       // Exp = I + a K + b K^2
    const auto J = combine(D3(1.0), -c.b, c.c, p);      // Jr = I - b K + c K^2
    const auto Ji = combine(D3(1.0), D3(0.5), c.d, p);  // Jr^-1 = I + K/2 + d K^2
    const Eigen::Matrix3d E0 = so3::exp(phi), J0 = so3::right_jacobian(phi),
                          Ji0 = so3::right_jacobian_inverse(phi);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(E[3 * i + j].v, E0(i, j), kRoundOff);
        EXPECT_NEAR(J[3 * i + j].v, J0(i, j), kRoundOff);
        EXPECT_NEAR(Ji[3 * i + j].v, Ji0(i, j), kRoundOff);
      }
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d dJi_fd = (so3::right_jacobian_inverse(phi + 1e-6 * Vector3d::Unit(k)) -
                                      so3::right_jacobian_inverse(phi - 1e-6 * Vector3d::Unit(k))) /
                                     2e-6;
      for (int i = 0; i < 9; ++i) EXPECT_NEAR(Ji[i].d[k], dJi_fd(i / 3, i % 3), 1e-8);
    }
  }
}

}  // namespace
}  // namespace tcasim::beam_fe
