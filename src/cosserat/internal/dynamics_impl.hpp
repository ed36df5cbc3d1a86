#pragma once
/// Internal state of cosserat::RodDynamics shared by its source files (not installed, not part
/// of the public API): the state layout, the stage-point data of the BDF-alpha history, and
/// the solver's workspace. The files, one concept each:
///   dynamics.cpp          options, setup, loads, scales, initialize() and step() in time,
///                         variable steps, the local error estimate and undo_step();
///   dynamics_rhs.cpp      the time-discretized rod equations at one point and their Jacobian;
///   dynamics_shooting.cpp RK4 over the grid, the multiple-shooting residual and Jacobian;
///   dynamics_newton.cpp   the Newton (chord) iterations of one solve;
///   dynamics_outputs.cpp  energies, tensions, elongations and the tip.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/internal/dynamics_section.hpp"
#include "cosserat/internal/string_system.hpp"
#include "tca/tca.hpp"

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
/// What rhs_residual() reads of a section in one solve (c0 and the gravity fixed), computed as
/// it did per call: the inverse effective stiffnesses 1 / (K + c0 B), K_bt omega* and the
/// weight per length rho A g.
struct SectionConstants {
  Vec3 Kt_se_inv = Vec3::Zero(), Kt_bt_inv = Vec3::Zero();
  Vec3 K_bt_omega_star = Vec3::Zero(), f_W = Vec3::Zero();
};
/// History (or time derivative) of the differentiated quantities at one point.
struct PointRates {
  Vec3 e = Vec3::Zero(), omega = Vec3::Zero(), q = Vec3::Zero(), w = Vec3::Zero();
};

/// df/dy of rhs() at one stage, kept in factors (the product with the sensitivities is about
/// half the flops of the dense D x D matrix and skips its assembly):
///   df/dy = A_direct + Fx Z (E_NM + sum_j v_j e_(kT + j)^T),
/// A_direct the derivative at fixed strains xi = (e, omega) (3 x 3 blocks), Fx = df/dxi
/// (D x 6), Z = dxi/d(N, M) from the section's constitutive law, E_NM the (N, M) rows of the
/// state and v_j = -c_i (qh_i, r_i x qh_i) the strains' dependence on TCA tension j (zero
/// where its string does not run).
struct StageJacobian {
  internal::Mat3 Om, hat_nu, B_NQ, B_NW, B_MW;  // hat(omega), hat(nu) and the inertia blocks
  Vec3 nu, f_W;
  internal::Mat6 Z;
  Eigen::Matrix<double, Eigen::Dynamic, 6> Fx;
  std::vector<internal::Vec6> v;
  int kT = 0;
  /// dK = (df/dy) dY (dY: D x m).
  void apply(const Eigen::MatrixXd& dY, Eigen::MatrixXd& dK) const;
};

// Classical RK4: stage nodes c and the multipliers of the previous stage.
constexpr double kStageC[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageA[4] = {0.0, 0.5, 0.5, 1.0};
constexpr double kStageB[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
/// DynamicsOptions::SpatialScheme::kEuler: one stage (slot 4 i), weight 1.
constexpr double kEulerB[4] = {1.0, 0.0, 0.0, 0.0};
/// Up to this many unknowns the Newton system is factorized densely (partial pivoting):
/// faster than SparseLU at that size, the same solution.
constexpr int kDenseUnknowns = 300;
/// Chord iterations with one factorization before a fresh Jacobian is computed.
constexpr int kStaleIterations = 6;
/// The sections' constitutive solve with strings (rhs()) on the residual-only path stops after a
/// Newton correction below this relative size (the next one, of order its square, would be at
/// round-off).
constexpr double kQuadraticStop = 1e-8;
/// Highest order of the extrapolated start of a time step (RodDynamics::Impl::predict): the
/// polynomial through the last kMaxPredictorOrder + 1 solutions. Measured on the released steel
/// cantilever (dt = 2 ms): Newton iterations per step fall from 5.1 (order 2 fixed) to 2.6 with
/// the order chosen among 0..8; higher orders gain nothing more.
constexpr int kMaxPredictorOrder = 8;
/// Most TCA-driven actuators of one model (scratch arrays on the stack).
constexpr int kMaxTcas = 64;

}  // namespace dynamics

struct RodDynamics::Impl {
  Impl(const rod::RodModel& m, const DynamicsOptions& o);

  // --- the discretization
  /// Right-hand side at arc length s of state y with the history of stage slot `slot`;
  /// the stage's strains and velocities are written to trial[slot]. With A: the Jacobian
  /// df/dy in its factors. False when the section's constitutive solve fails or y is not
  /// finite.
  bool rhs(double s, const Eigen::VectorXd& y, int slot, Eigen::VectorXd& dy,
           dynamics::StageJacobian* A);
  /// The right-hand side of rhs() without the Jacobian, on raw arrays of D doubles and without
  /// allocations (the residual-only path of evaluate()). Strings under tension (the section's
  /// constitutive solve with the strings) are passed on to rhs().
  bool rhs_residual(double s, const double* y, int slot, double* dy);
  /// Integrates interval k from y (its S RK4 steps), writing the grid states; Phi: when
  /// non-null, the sensitivity of y_end to node k's unknowns (column c: by state component
  /// unknown_state(k, c); D x n0() at the base, D x D elsewhere).
  bool integrate_interval(int k, Eigen::VectorXd& y, Eigen::MatrixXd* Phi);
  /// integrate_interval without sensitivities, by rhs_residual() (y: D doubles, in place).
  bool integrate_interval_residual(int k, double* y);
  /// State at node k from the unknowns z.
  void node_state(const Eigen::VectorXd& z, int k, Eigen::VectorXd& y) const;
  /// Scaled residual at z; with `jacobian`, also the scaled Jacobian into J_.
  bool evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& r, bool jacobian);
  /// Tip residual rows (6) of the end state and, with G, their derivative (6 x D).
  /// With TCA strings also their laws (n_tca rows); false where a TCA law has no state.
  bool tip_residual(const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> r,
                    Eigen::MatrixXd* G) const;
  /// Newton (chord) iterations from z.
  DynamicsSummary solve(Eigen::VectorXd& z);
  /// Scale of each unknown (the state scales of its component): Newton's step is dz = scale u.
  Eigen::VectorXd unknown_scale() const;
  /// unknown_scale() into s (resized to unknowns()).
  void unknown_scale(Eigen::VectorXd& s) const;
  void set_loads(const rod::Loads& loads);
  void set_scales();
  /// The SectionConstants of every section for the current c0_active and g_W (after
  /// set_loads(), before a solve).
  void set_section_constants();
  int n0() const { return 6 + n_tca; }  // unknowns at the base: N, M, TCA tensions
  /// The state component of node k's unknown c: (N, M) then the TCA tensions at the base
  /// (k = 0), the state itself elsewhere.
  int unknown_state(int k, int c) const {
    return k > 0 ? c : c < 6 ? dynamics::kN + c : kT + c - 6;
  }
  int unknowns() const { return n0() + (M - 1) * D; }
  int slots() const { return 4 * N + 1; }  // 4 stages per step, then the tip point
  /// Body properties at stage slot `slot` (the tip point is slot 4 N).
  const dynamics::SectionAt& section_of(int slot) const { return uniform ? sec : slot_sec[slot]; }
  /// Length of RK4 step i [m].
  double step_length(int i) const { return uniform ? h : s_grid[i + 1] - s_grid[i]; }

  const rod::RodModel& model;
  DynamicsOptions opt;
  dynamics::SectionAt sec;  // at s = 0 (everywhere when `uniform`); sets the scales
  bool uniform = true;      // dynamics::section_is_uniform
  /// Varying body: the properties at every stage slot (the end stage of a step and the tip
  /// take the limit from the left at a jump).
  std::vector<dynamics::SectionAt> slot_sec;
  /// set_section_constants(): of `sec` (uniform), else per stage slot.
  dynamics::SectionConstants sec_c;
  std::vector<dynamics::SectionConstants> slot_sec_c;
  const dynamics::SectionConstants& constants_of(int slot) const {
    return uniform ? sec_c : slot_sec_c[static_cast<std::size_t>(slot)];
  }
  double tip_mass_kg = 0.0;  // options' or the model's
  int n_act = 0, D = 0, N = 0, M = 0, S = 0;
  // Stages per step along s and their weights (RK4: 4 and kStageB; forward Euler: 1 and
  // kEulerB); a step keeps 4 stage slots either way.
  int stages = 4;
  const double* stage_b = dynamics::kStageB;
  // TCA strings: their tensions are states T_j (constant along s) at kT + j, unknowns at the
  // base, fixed by the TCA law at the tip; tca_actuator[j] is the actuator of T_j and
  // tca_slot[i] the j of actuator i (-1: tension drive).
  int n_tca = 0, kT = 0;
  std::vector<int> tca_actuator, tca_slot;
  std::vector<std::vector<tca::Segment>> segments;  // per actuator: the current temperatures
  // Electric drives: per actuator and segment, the thermal state [K] advanced with the steps.
  std::vector<std::vector<double>> temperatures_K;
  double L = 0.0, h = 0.0;     // h = L / N (the step of a uniform body)
  std::vector<double> s_grid;  // N + 1 grid points; s_grid[i] = i h on a uniform body
  // BDF-alpha: y_t(n+1) = c0 y(n+1) + c1 y(n) + c2 y(n-1) + d1 y_t(n) ([Till2019]).
  double c0 = 0.0, c1 = 0.0, c2 = 0.0, d1 = 0.0;
  /// c0, c1, c2, d1 of a step of size dt after one of size k (docs/conventions.md "Variable
  /// time steps (shooting)"); k == dt gives [Till2019]'s constant-step numbers bit for bit.
  void set_step_coefficients(double dt, double k);
  /// Sizes of the last two converged steps [s] (0: none since initialize(), the history is
  /// the state at rest).
  double dt_last[2] = {0.0, 0.0};
  /// What the error estimate of the last converged step needs besides grid_converged (it is
  /// computed when local_error_m() asks: fixed-step runs do not pay for it): whether there is
  /// such a step, its size and the two before (dt, k, k2).
  struct ErrorData {
    bool stepped = false;
    double dt[3] = {0.0, 0.0, 0.0};
  };
  ErrorData est;
  /// Position and rotation (p_W, R_WB column-major) at the grid nodes one, two and three steps
  /// before grid_converged (at rest before the first steps): the history of the estimate.
  std::vector<Eigen::Matrix<double, 12, 1>> node_hist[3];
  mutable double local_error = 0.0;  // the estimate, once computed
  mutable bool local_error_done = true;
  /// The estimated local error of the last converged step (RodDynamics::local_error_m).
  double local_error_estimate() const;
  /// Intervals M of the automatic rule for growth rate kappa (the fewest dividing N whose
  /// longest interval l has l kappa <= max_interval_growth; N when none does).
  int automatic_intervals(double kappa) const;
  /// Length of the longest of the M shooting intervals [m].
  double longest_interval() const;
  /// Switches to m intervals (the unknowns of the converged grid in the new layout; the
  /// extrapolated start restarts; a fresh Jacobian).
  void set_intervals(int m);
  /// Factorizes the Jacobian in J_dense_ (dense) or J_ (sparse): lu_valid, lu_c0 and the
  /// banded factors of dense_solve().
  void factorize_jacobian();
  /// What undo_step() restores: the state before the last step() (the factorization only
  /// when that step replaced it: saved at its first fresh Jacobian).
  struct Snapshot {
    bool valid = false;
    double t = 0.0, dt_last[2] = {0.0, 0.0}, local_error = 0.0;
    bool local_error_done = true;
    ErrorData est;
    std::vector<std::vector<double>> temperatures_K;
    // The loads of the last solve (the outputs read them).
    std::vector<std::vector<tca::Segment>> segments;
    std::vector<double> cT;
    internal::Vec3 f_ext_W, F_tip_W, M_tip_W, g_W;
    std::vector<dynamics::PointData> cur, prev;
    std::vector<dynamics::PointRates> cur_t;
    Eigen::VectorXd z;
    std::vector<Eigen::VectorXd> z_diff, grid_converged;
    std::vector<Eigen::Matrix<double, 12, 1>> node_hist[3];
    int history_steps = 0, predictor_order = 0, M = 0;
    bool lu_pending = false;  // no fresh Jacobian in the step yet
    bool lu_saved = false, lu_valid = false;
    double lu_c0 = -1.0;
    Eigen::MatrixXd J_dense;
    Eigen::SparseMatrix<double> J;
  };
  Snapshot snap;
  void save_snapshot();
  double c0_active = 0.0;  // 0 for the static solve
  double t = 0.0;
  // Loads of the current solve.
  internal::Vec3 f_ext_W = internal::Vec3::Zero();  // rho A g of `sec`
  internal::Vec3 F_tip_W = internal::Vec3::Zero();
  internal::Vec3 M_tip_W = internal::Vec3::Zero(), g_W = internal::Vec3::Zero();
  std::vector<double> cT;       // count * tension per actuator (tension drives)
  std::vector<double> cT_eval;  // rhs scratch: cT with the TCA tensions of the state
  std::vector<double> length_ratio, count;
  // Strings anchored inside the body or with spline routings (docs/conventions.md "Rod
  // dynamics (shooting method)"): the anchors and spline knots are grid nodes; step_runs[i]
  // says which strings run along RK4 step i (none outside its span), and the routing is read
  // on the step's side of a knot (a linear spline's direction jumps there).
  bool string_knots = false;
  std::vector<std::vector<char>> step_runs;
  /// Whether actuator a's string runs at stage slot `slot` (the tip slot: the last step).
  bool runs(int slot, int a) const {
    return !string_knots || step_runs[static_cast<std::size_t>(std::min(slot / 4, N - 1))]
                                     [static_cast<std::size_t>(a)] != 0;
  }
  /// Arc length and side at which the routing is read at stage slot `slot` (s: the stage's).
  double routing_s(int slot, double s) const {
    if (!string_knots) return s;
    if (slot >= 4 * N) return L;
    return slot % 4 == 3 ? s_grid[static_cast<std::size_t>(slot / 4 + 1)]
                         : (slot % 4 == 0 ? s_grid[static_cast<std::size_t>(slot / 4)] : s);
  }
  rod::Side routing_side(int slot) const {
    return slot >= 4 * N || slot % 4 == 3 ? rod::Side::kLeft : rod::Side::kRight;
  }
  double F_c = 1.0;
  Eigen::VectorXd scale;        // per state component (D)
  Eigen::ArrayXd inv_scale_;    // 1 / scale
  Eigen::VectorXd scale_z_;     // unknown_scale() of the current scales (set_scales)
  Eigen::ArrayXd inv_scale_z_;  // 1 / scale_z_
  // Per slot: history of the current step, data of the last evaluation (trial), of the
  // last two converged steps and the time derivative at the last one.
  std::vector<dynamics::PointRates> hist, cur_t;
  std::vector<dynamics::PointData> trial, cur, prev;
  std::vector<Eigen::VectorXd> grid;  // N + 1 states of the last evaluation
  std::vector<Eigen::VectorXd> grid_converged;
  Eigen::VectorXd z;
  /// Backward differences of the solutions (z_diff[j] = nabla^j z, j = 0 .. min(history_steps,
  /// kMaxPredictorOrder); z_diff[0] = z): the history of the extrapolated start.
  std::vector<Eigen::VectorXd> z_diff;
  /// After a converged step to z_new: z_diff becomes the differences of z_new.
  void push_difference(const Eigen::VectorXd& z_new);
  int history_steps = 0;    // converged steps behind z (for the extrapolated start)
  int predictor_order = 0;  // the order of predict() that would have started the last step best
  /// Start of the next step: the polynomial of degree p through z and the p solutions before it
  /// evaluated one step ahead, sum_{j <= p} z_diff[j] (p <= history_steps), into out.
  void predict(int p, Eigen::VectorXd& out) const;
  /// After a converged step to `z_new`: the predictor order that would have come closest to it
  /// (scaled max norm, orders 0 .. min(kMaxPredictorOrder, history_steps)).
  int best_predictor_order(const Eigen::VectorXd& z_new);
  // Jacobian (scaled) and its factorization.
  Eigen::SparseMatrix<double> J_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool pattern_analyzed = false, lu_valid = false;
  bool dense = false;  // unknowns() <= kDenseUnknowns: dense LU instead of SparseLU
  Eigen::MatrixXd J_dense_;
  // Residual-only path: scratch states (D each) and each actuator's routing r, r' at every
  // stage slot ([slot * n_act + i]).
  Eigen::VectorXd ws_y_, ws_dy_, ws_stage_, ws_k_, ws_acc_, ws_node_, ws_next_;
  dynamics::StageJacobian ws_jacobian_;  // integrate_interval()'s stage Jacobian
  std::vector<internal::Vec3> slot_r_, slot_dr_;
  /// Actuator a's routing r, r' as rhs() reads it at stage slot `slot` (routing_s, routing_side
  /// at the slot's arc length; evaluated once in the constructor).
  const internal::Vec3& slot_r(int slot, int a) const {
    return slot_r_[static_cast<std::size_t>(slot * n_act + a)];
  }
  const internal::Vec3& slot_dr(int slot, int a) const {
    return slot_dr_[static_cast<std::size_t>(slot * n_act + a)];
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu_;
  /// The dense factors by rows, with the band each row of them occupies: row i of L (unit
  /// lower) has its nonzeros in columns [lu_first_[i], i), row i of U in [i, lu_last_[i]).
  /// The multiple-shooting matrix is block bidiagonal, so the factors are banded.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> lu_rows_;
  std::vector<int> lu_first_, lu_last_;
  /// Dense Newton system: x = J^-1 b by the factors (x and b distinct, of unknowns()).
  void dense_solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  // solve()'s and step()'s workspace (kept between steps: no allocations per step).
  Eigen::VectorXd r_, z_old_, dz_, u_, z_start_, ws_predict_, ws_carry_, ws_next_diff_;
  std::vector<std::vector<double>> T_old_;
  double lu_c0 = -1.0;
  std::vector<Eigen::Triplet<double>> triplets_;
};

/// The names every dynamics source file uses (one `using namespace dynamics_names;` each).
namespace dynamics_names {
using internal::hat;
using internal::Mat3;
using internal::Mat6;
using internal::Vec3;
using internal::Vec6;
using namespace dynamics;
}  // namespace dynamics_names

}  // namespace tcasim::cosserat
