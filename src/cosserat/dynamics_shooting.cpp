// Rod dynamics: RK4 over each shooting interval with its forward sensitivities, the tip
// balance, and the multiple-shooting residual and Jacobian (assembled and factorized).
#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "cosserat/internal/dynamics_impl.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

bool RodDynamics::Impl::integrate_interval(int k, Eigen::VectorXd& y, Eigen::MatrixXd* Phi) {
  Eigen::VectorXd Y(D), kj(D), acc(D);
  Eigen::MatrixXd dY, dK, dacc;
  StageJacobian& A = ws_jacobian_;
  if (Phi) {
    // The derivatives by the node's unknowns only: at the base (k = 0) the n0() columns of
    // (N, M) and the TCA tensions (column c is state component unknown_state(0, c)), a
    // quarter of the state's; elsewhere the whole state.
    const int m = k == 0 ? n0() : D;
    Phi->setZero(D, m);
    for (int c = 0; c < m; ++c) (*Phi)(unknown_state(k, c), c) = 1.0;
    dY.resize(D, m);
    dK.resize(D, m);
    dacc.resize(D, m);
  }
  for (int i = k * S; i < (k + 1) * S; ++i) {
    grid[i] = y;
    const double s = s_grid[i], hs = step_length(i);
    acc.setZero();
    if (Phi) dacc.setZero();
    for (int j = 0; j < stages; ++j) {
      if (j == 0) {
        Y = y;
      } else {
        Y = y + (kStageA[j] * hs) * kj;
        if (Phi) dY = *Phi + (kStageA[j] * hs) * dK;
      }
      if (!rhs(s + kStageC[j] * hs, Y, 4 * i + j, kj, Phi ? &A : nullptr)) return false;
      if (!std::isfinite(kj.sum())) return false;
      acc += stage_b[j] * kj;
      if (Phi) {
        A.apply(j == 0 ? *Phi : dY, dK);  // dK = (df/dy) dY
        dacc += stage_b[j] * dK;
      }
    }
    y += hs * acc;
    if (Phi) *Phi += hs * dacc;
  }
  if (k == M - 1) grid[N] = y;
  return y.allFinite();
}

bool RodDynamics::Impl::integrate_interval_residual(int k, double* y) {
  // integrate_interval()'s RK4 with its numbers (the same operations on each component), on
  // the scratch states; one pass per stage accumulates the step and forms the next stage
  // state (the last one also the step's end). A non-finite stage derivative makes the step's
  // end non-finite (the operations keep NaN and infinity), so each step's end is checked.
  double* __restrict Y = ws_stage_.data();
  double* __restrict kj = ws_k_.data();
  double* __restrict acc = ws_acc_.data();
  for (int i = k * S; i < (k + 1) * S; ++i) {
    std::copy(y, y + D, grid[i].data());
    const double s = s_grid[i], hs = step_length(i);
    for (int j = 0; j < stages; ++j) {
      // (the first stage at y itself)
      if (!rhs_residual(s + kStageC[j] * hs, j == 0 ? y : Y, 4 * i + j, kj)) return false;
      const double b = stage_b[j];
      if (j + 1 < stages) {
        const double a = kStageA[j + 1] * hs;
        if (j == 0) {
          for (int c = 0; c < D; ++c) {
            acc[c] = b * kj[c];
            Y[c] = y[c] + a * kj[c];
          }
        } else {
          for (int c = 0; c < D; ++c) {
            acc[c] += b * kj[c];
            Y[c] = y[c] + a * kj[c];
          }
        }
      } else if (j == 0) {  // one stage (forward Euler)
        for (int c = 0; c < D; ++c) {
          acc[c] = b * kj[c];
          y[c] += hs * acc[c];
        }
      } else {
        for (int c = 0; c < D; ++c) {
          acc[c] += b * kj[c];
          y[c] += hs * acc[c];
        }
      }
    }
    bool finite = true;
    for (int c = 0; c < D; ++c) finite = finite && std::isfinite(y[c]);
    if (!finite) return false;
  }
  if (k == M - 1) std::copy(y, y + D, grid[N].data());
  return true;
}

void RodDynamics::Impl::node_state(const Eigen::VectorXd& zz, int k, Eigen::VectorXd& y) const {
  if (k == 0) {
    y.setZero(D);
    y.segment<3>(kP) = model.base_position_W_m;
    Eigen::Map<Mat3>(y.data() + kR) = model.R_WB0;
    y.segment<6>(kN) = zz.head<6>();
    for (int j = 0; j < n_tca; ++j) y[kT + j] = zz[6 + j];
    return;
  }
  y = zz.segment(n0() + (k - 1) * D, D);
}

bool RodDynamics::Impl::tip_residual(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> r,
                                     Eigen::MatrixXd* G) const {
  // Balance of the tip section and the tip mass m_t (docs/conventions.md):
  //   N(L) = R^T (F_e + m_t g) - m_t (q_t + w x q),   M(L) = R^T M_e.
  const Eigen::Map<const Mat3> R(y.data() + kR);
  const Vec3 q = y.segment<3>(kQ), w = y.segment<3>(kW);
  const double mt = tip_mass_kg;
  const PointRates& H = hist[4 * N];
  const Vec3 F = F_tip_W + mt * g_W;
  const Vec3 q_t = c0_active * q + H.q;
  r.head<3>() = (y.segment<3>(kN) - R.transpose() * F + mt * (q_t + w.cross(q))) / F_c;
  r.segment<3>(3) = (y.segment<3>(kM) - R.transpose() * M_tip_W) / (F_c * L);
  // TCA strings: the law phi(T, delta(L)) = 0 between the tension and the elongation, with
  // coil contact (tca::contact_residual, as in statics).
  double dphi_dT[kMaxTcas], dphi_ddelta[kMaxTcas];
  for (int j = 0; j < n_tca; ++j) {
    const int i = tca_actuator[j];
    try {
      const tca::ContactResidual c = tca::contact_residual(*model.actuators[i].drive.tca, y[kT + j],
                                                           y[kDelta + i], segments[i]);
      r[6 + j] = c.phi_N / F_c;
      dphi_dT[j] = c.dphi_dF;
      dphi_ddelta[j] = c.dphi_ddelta_N_m;
    } catch (const DomainError&) {
      return false;
    }
  }
  if (!G) return true;
  G->setZero(6 + n_tca, D);
  for (int j = 0; j < n_tca; ++j) {
    (*G)(6 + j, kT + j) = dphi_dT[j] / F_c;
    (*G)(6 + j, kDelta + tca_actuator[j]) = dphi_ddelta[j] / F_c;
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      (*G)(j, kR + 3 * j + i) = -F[i] / F_c;
      (*G)(3 + j, kR + 3 * j + i) = -M_tip_W[i] / (F_c * L);
    }
  }
  G->block<3, 3>(0, kN) = Mat3::Identity() / F_c;
  G->block<3, 3>(0, kQ) = mt * (c0_active * Mat3::Identity() + hat(w)) / F_c;
  G->block<3, 3>(0, kW) = -mt * hat(q) / F_c;
  G->block<3, 3>(3, kM) = Mat3::Identity() / (F_c * L);
  return true;
}

bool RodDynamics::Impl::evaluate(const Eigen::VectorXd& zz, Eigen::VectorXd& r, bool jacobian) {
  const int n = unknowns();
  r.resize(n);
  Eigen::VectorXd &y = ws_node_, &y_next = ws_next_;
  Eigen::MatrixXd Phi, G;
  if (jacobian) triplets_.clear();
  const Eigen::ArrayXd& inv_scale = inv_scale_;
  for (int k = 0; k < M; ++k) {
    node_state(zz, k, y);
    const bool ok =
        jacobian ? integrate_interval(k, y, &Phi) : integrate_interval_residual(k, y.data());
    if (!ok) return false;
    const int row = k * D;  // continuity rows of node k + 1; the tip rows after the last
    const int col0 = k == 0 ? 0 : n0() + (k - 1) * D;
    // Columns of node k's unknowns: (N, M) and the TCA tensions at the base, the whole state
    // elsewhere; column c of Phi is the derivative by state component unknown_state(k, c).
    const int ncols = k == 0 ? n0() : D;
    if (k < M - 1) {
      node_state(zz, k + 1, y_next);
      r.segment(row, D) = ((y - y_next).array() * inv_scale).matrix();
      if (jacobian) {
        const int col1 = n0() + k * D;
        for (int c = 0; c < ncols; ++c) {
          const int sc = unknown_state(k, c);
          for (int rr = 0; rr < D; ++rr) {
            triplets_.emplace_back(row + rr, col0 + c, Phi(rr, c) * scale[sc] * inv_scale[rr]);
          }
        }
        for (int rr = 0; rr < D; ++rr) triplets_.emplace_back(row + rr, col1 + rr, -1.0);
      }
    } else {
      // The tip point's strains (energies, damping history) and the tip residual.
      Eigen::VectorXd& dy = ws_acc_;
      if (!rhs_residual(L, y.data(), 4 * N, dy.data())) return false;
      if (!tip_residual(y, r.segment(row, n0()), jacobian ? &G : nullptr)) return false;
      if (jacobian) {
        const Eigen::MatrixXd GP = G * Phi;
        for (int c = 0; c < ncols; ++c) {
          const int sc = unknown_state(k, c);
          for (int rr = 0; rr < n0(); ++rr) {
            triplets_.emplace_back(row + rr, col0 + c, GP(rr, c) * scale[sc]);
          }
        }
      }
    }
  }
  if (!r.allFinite()) return false;
  if (jacobian) {
    // undo_step() restores the factorization this step replaces: keep its matrix once.
    if (snap.lu_pending) {
      snap.lu_pending = false;
      snap.lu_saved = true;
      snap.lu_valid = lu_valid;
      snap.lu_c0 = lu_c0;
      if (lu_valid && dense) snap.J_dense = J_dense_;
      if (lu_valid && !dense) snap.J = J_;
    }
    if (dense) {
      J_dense_.setZero(n, n);
      for (const auto& tr : triplets_) J_dense_(tr.row(), tr.col()) += tr.value();
    } else {
      J_.resize(n, n);
      J_.setFromTriplets(triplets_.begin(), triplets_.end());
      J_.makeCompressed();
    }
    factorize_jacobian();
  }
  return true;
}

void RodDynamics::Impl::factorize_jacobian() {
  if (dense) {
    const int n = static_cast<int>(J_dense_.rows());
    dense_lu_.compute(J_dense_);
    // PartialPivLU does not report singularity: check the pivots.
    const Eigen::VectorXd piv = dense_lu_.matrixLU().diagonal().cwiseAbs();
    lu_valid = piv.allFinite() && piv.minCoeff() > 1e-14 * piv.maxCoeff();
    lu_c0 = c0_active;
    // The factors by rows and their bands (for dense_solve()).
    lu_rows_ = dense_lu_.matrixLU();
    lu_first_.resize(n);
    lu_last_.resize(n);
    for (int i = 0; i < n; ++i) {
      int first = 0, last = n;
      while (first < i && lu_rows_(i, first) == 0.0) ++first;
      while (last > i + 1 && lu_rows_(i, last - 1) == 0.0) --last;
      lu_first_[i] = first;
      lu_last_[i] = last;
    }
    return;
  }
  if (!pattern_analyzed) {
    lu_.analyzePattern(J_);
    pattern_analyzed = true;
  }
  lu_.factorize(J_);
  lu_valid = lu_.info() == Eigen::Success;
  lu_c0 = c0_active;
}

void RodDynamics::Impl::dense_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  // P J = L U: x = U^-1 L^-1 P b, each row's dot product over its band only (the same solution
  // as PartialPivLU::solve up to the order of the sums).
  const int n = static_cast<int>(lu_rows_.rows());
  x.noalias() = dense_lu_.permutationP() * b;
  for (int i = 1; i < n; ++i) {
    const int f = lu_first_[i];
    x[i] -= lu_rows_.row(i).segment(f, i - f).dot(x.segment(f, i - f));
  }
  for (int i = n - 1; i >= 0; --i) {
    const int len = lu_last_[i] - i - 1;
    x[i] = (x[i] - lu_rows_.row(i).segment(i + 1, len).dot(x.segment(i + 1, len))) / lu_rows_(i, i);
  }
}

}  // namespace tcasim::cosserat
