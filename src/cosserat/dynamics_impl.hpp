#pragma once
/// Internal state of cosserat::RodDynamics shared by its source files (not installed, not part
/// of the public API): the state layout, the stage-point data of the BDF-alpha history, and
/// the solver's workspace. The files, one concept each:
///   dynamics.cpp          options, setup, loads, scales, initialize() and step() in time;
///   dynamics_rhs.cpp      the time-discretized rod equations at one point and their Jacobian;
///   dynamics_shooting.cpp RK4 over the grid, the multiple-shooting residual and Jacobian;
///   dynamics_newton.cpp   the Newton (chord) iterations of one solve;
///   dynamics_outputs.cpp  energies, tensions, elongations and the tip.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/dynamics_section.hpp"
#include "cosserat/string_system.hpp"

namespace tcasim::cosserat {

namespace dynamics {

using internal::Vec3;

// State layout (dynamics.hpp).
constexpr int kP = 0, kR = 3, kN = 12, kM = 15, kQ = 18, kW = 21, kDelta = 24;

/// What a stage point (or the tip point) keeps: the strains and velocities whose time
/// derivatives the BDF-alpha formula needs, e = nu - nu* (the deviation, as in the static
/// solver: no cancellation), omega, q, w, and the position p for the energies.
struct PointData {
  Vec3 e = Vec3::Zero(), omega = Vec3::Zero(), q = Vec3::Zero(), w = Vec3::Zero();
  Vec3 p = Vec3::Zero();
};
/// History (or time derivative) of the differentiated quantities at one point.
struct PointRates {
  Vec3 e = Vec3::Zero(), omega = Vec3::Zero(), q = Vec3::Zero(), w = Vec3::Zero();
};

// Classical RK4: stage nodes c and the multipliers of the previous stage.
constexpr double kStageC[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageA[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageB[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
/// Up to this many unknowns the Newton system is factorized densely (partial pivoting):
/// faster than SparseLU at that size, the same solution.
constexpr int kDenseUnknowns = 300;
/// Chord iterations with one factorization before a fresh Jacobian is computed.
constexpr int kStaleIterations = 6;

}  // namespace dynamics

struct RodDynamics::Impl {
  Impl(const rod::RodModel& m, const DynamicsOptions& o);

  // --- the discretization
  /// Right-hand side at arc length s of state y with the history of stage slot `slot`;
  /// the stage's strains and velocities are written to trial[slot]. With A: the Jacobian
  /// df/dy (D x D). False when the section's constitutive solve fails or y is not finite.
  bool rhs(double s, const Eigen::VectorXd& y, int slot, Eigen::VectorXd& dy, Eigen::MatrixXd* A);
  /// Integrates interval k from y (its S RK4 steps), writing the grid states; Phi: the
  /// sensitivity dy_end/dy0 (D x D) when non-null.
  bool integrate_interval(int k, Eigen::VectorXd& y, Eigen::MatrixXd* Phi);
  /// State at node k from the unknowns z.
  void node_state(const Eigen::VectorXd& z, int k, Eigen::VectorXd& y) const;
  /// Scaled residual at z; with `jacobian`, also the scaled Jacobian into J_.
  bool evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& r, bool jacobian);
  /// Tip residual rows (6) of the end state and, with G, their derivative (6 x D).
  void tip_residual(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> r,
                    Eigen::MatrixXd* G) const;
  /// Newton (chord) iterations from z.
  DynamicsSummary solve(Eigen::VectorXd& z);
  void set_loads(const rod::Loads& loads);
  void set_scales();
  int unknowns() const { return 6 + (M - 1) * D; }
  int slots() const { return 4 * N + 1; }  // 4 stages per step, then the tip point

  const rod::RodModel& model;
  DynamicsOptions opt;
  dynamics::SectionAt sec;  // uniform along s (dynamics::section_is_uniform)
  int n_act = 0, D = 0, N = 0, M = 0, S = 0;
  double L = 0.0, h = 0.0;
  // BDF-alpha: y_t(n+1) = c0 y(n+1) + c1 y(n) + c2 y(n-1) + d1 y_t(n) ([Till2019]).
  double c0 = 0.0, c1 = 0.0, c2 = 0.0, d1 = 0.0;
  double c0_active = 0.0;  // 0 for the static solve
  double t = 0.0;
  // Loads of the current solve.
  internal::Vec3 f_ext_W = internal::Vec3::Zero(), F_tip_W = internal::Vec3::Zero();
  internal::Vec3 M_tip_W = internal::Vec3::Zero(), g_W = internal::Vec3::Zero();
  std::vector<double> cT;  // count * tension per actuator
  std::vector<double> length_ratio, count;
  double F_c = 1.0;
  Eigen::VectorXd scale;  // per state component (D)
  // Per slot: history of the current step, data of the last evaluation (trial), of the
  // last two converged steps and the time derivative at the last one.
  std::vector<dynamics::PointRates> hist, cur_t;
  std::vector<dynamics::PointData> trial, cur, prev;
  std::vector<Eigen::VectorXd> grid;  // N + 1 states of the last evaluation
  std::vector<Eigen::VectorXd> grid_converged;
  Eigen::VectorXd z, z_prev, z_prev2;
  int history_steps = 0;  // converged steps behind z (for the extrapolated start)
  // Jacobian (scaled) and its factorization.
  Eigen::SparseMatrix<double> J_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool pattern_analyzed = false, lu_valid = false;
  bool dense = false;  // unknowns() <= kDenseUnknowns: dense LU instead of SparseLU
  Eigen::MatrixXd J_dense_;
  Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu_;
  double lu_c0 = -1.0;
  std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace tcasim::cosserat
