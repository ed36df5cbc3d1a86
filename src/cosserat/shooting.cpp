#include "cosserat/shooting.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "cosserat/lie_rkmk4.hpp"
#include "cosserat/planar.hpp"

namespace tcasim::cosserat {

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

using namespace state_layout;

/// Armijo constant of the backtracking line search on phi = ||r||^2 / 2 (Newton's
/// direction d solves J d = -r, so phi'(0) = -2 phi: accept phi(t) <= (1 - 2 c t) phi).
constexpr double kArmijo = 1e-4;
/// Relative finite-difference steps: sqrt(eps) (forward) and eps^(1/3) (central)
/// balance truncation and round-off errors.
/// With a Broyden-updated (stale) Jacobian, at most this many halvings before the
/// Jacobian is recomputed by differences.
constexpr int kStaleLineSearchSteps = 1;
/// A stale-Jacobian step that reduces ||r|| by less than this factor discards the
/// Jacobian (the next iteration recomputes it).
constexpr double kBroydenMinReduction = 0.5;
/// Forward sensitivities keep their 6 x nx work matrix on the stack: at most this many
/// unknowns (10 TCA drives); beyond, the solver uses forward differences instead.
constexpr int kMaxSensitivityUnknowns = 16;
/// Scaled residual to which the coarse level is converged: coarse IVPs are cheap, and the
/// coarse-grid correction of a warm start is only as accurate as the coarse solutions.
constexpr double kCoarseTolerance = 1e-9;
/// A cold start hands the coarse (or middle) level's Jacobian to the next level only if it
/// was Broyden-updated at most this many times since it was computed.
constexpr int kMaxHandedOverUpdates = 1;
/// Initial guess with gravity: nodes of the load-strain quadrature, fixed-point
/// iterations, and the convergence test on the change of the mean strains (relative to
/// 1/L + their size).
constexpr int kGuessNodes = 8;
constexpr int kGuessIterations = 12;
constexpr double kGuessTolerance = 1e-3;
/// Path extrapolation (ShootingSolver::kPathHistory): relative distance from the line below
/// which an earlier actuation counts as on it, and the smallest spacing of the path's
/// parameters in units of the new step.
constexpr double kPathCollinearity = 1e-9;
constexpr double kPathMinSpacing = 0.5;
constexpr double kForwardStep = 1.4901161193847656e-08;  // sqrt(eps)
constexpr double kCentralStep = 6.0554544523933395e-06;  // eps^(1/3)

inline Mat3 hat(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

/// Solver of the symmetric 6x6 strain-derivative system M = [A B; B^T C] (fixed size, no
/// heap) by block elimination with Eigen's closed-form 3x3 inverses: S = C - B^T A^-1 B,
/// z_omega = S^-1 (b_omega - (A^-1 B)^T b_nu), z_nu = A^-1 b_nu - (A^-1 B) z_omega.
/// A = K_nu + sum A_i is positive definite unless strings are compressed beyond the
/// shear/axial stiffness; when A or S is numerically singular (relative determinant below
/// kSingularBlock) it falls back to LU with partial pivoting of M.
class StrainSystem {
 public:
  explicit StrainSystem(const Mat6& M) {
    const Mat3 A = M.topLeftCorner<3, 3>();
    const Mat3 B = M.topRightCorner<3, 3>();
    const Mat3 C = M.bottomRightCorner<3, 3>();
    block_ = well_conditioned(A);
    if (block_) {
      A_inv_ = A.inverse();
      AinvB_ = A_inv_ * B;
      const Mat3 S = C - B.transpose() * AinvB_;
      block_ = well_conditioned(S);
      if (block_) S_inv_ = S.inverse();
    }
    if (!block_) lu_.compute(M);
  }
  /// Solves M Z = R for a 6 x n right-hand side (in place).
  template <typename Rhs>
  void solve_in_place(Rhs& R) const {
    if (!block_) {
      R = lu_.solve(R);
      return;
    }
    const auto b_nu = R.template topRows<3>();
    const auto b_om = R.template bottomRows<3>();
    const Eigen::Matrix<double, 3, Rhs::ColsAtCompileTime, 0, 3, Rhs::MaxColsAtCompileTime> z_om =
        S_inv_ * (b_om - AinvB_.transpose() * b_nu);
    R.template topRows<3>() = A_inv_ * b_nu - AinvB_ * z_om;
    R.template bottomRows<3>() = z_om;
  }

 private:
  /// Relative determinant det(X) / prod(|X_ii|) below which a block counts as singular.
  static constexpr double kSingularBlock = 1e-10;
  static bool well_conditioned(const Mat3& X) {
    const double scale = std::abs(X(0, 0) * X(1, 1) * X(2, 2));
    const double det = X.determinant();
    return std::isfinite(det) && scale > 0.0 && std::abs(det) > kSingularBlock * scale;
  }
  bool block_ = false;
  Mat3 A_inv_, AinvB_, S_inv_;
  Eigen::PartialPivLU<Mat6> lu_;
};

/// The strain-derivative system M z = b with the structure of docs/conventions.md:
/// M = K + sum_i U_i A_i U_i^T, K = diag(K_nu, K_omega), U_i = [I; hat(r_i)] (6x3),
/// A_i = alpha_i (I - qh_i qh_i^T), alpha_i = c_i T_i / |q_i|. With one loaded string the
/// push-through (Woodbury) identity
///   M^-1 = K^-1 - K^-1 U (I + A G)^-1 A U^T K^-1,   G = U^T K^-1 U,
/// costs one 3x3 inverse and no 6x6 assembly; det M = det K det(I + A G), so I + A G is
/// singular exactly when M is. With several loaded strings, or when I + A G is numerically
/// singular, M is assembled and solved by StrainSystem.
class StringSystem {
 public:
  /// K_nu, K_omega and their reciprocals (precomputed by the caller).
  StringSystem(const Vec3& K_nu, const Vec3& K_omega, const Vec3& K_nu_inv, const Vec3& K_omega_inv)
      : kn_(K_nu), ko_(K_omega), kn_inv_(K_nu_inv), ko_inv_(K_omega_inv) {}
  /// Adds a loaded string at body offset r with A = alpha (I - qh qh^T).
  void add(const Vec3& r, double alpha, const Vec3& qh) {
    if (n_ == 0) {
      r_ = r;
      alpha_ = alpha;
      qh_ = qh;
    } else {
      if (n_ == 1) assemble(r_, alpha_, qh_);
      assemble(r, alpha, qh);
    }
    ++n_;
  }
  /// Factorizes after the last add.
  void factor() {
    if (n_ == 1) {
      // G = K_nu^-1 + hat(r)^T K_omega^-1 hat(r), written out (symmetric).
      const double x = r_.x(), y = r_.y(), z = r_.z();
      const Vec3& d = ko_inv_;
      Mat3 G;
      G << kn_inv_.x() + d.y() * z * z + d.z() * y * y, -d.z() * x * y, -d.y() * x * z,  //
          -d.z() * x * y, kn_inv_.y() + d.x() * z * z + d.z() * x * x, -d.x() * y * z,   //
          -d.y() * x * z, -d.x() * y * z, kn_inv_.z() + d.x() * y * y + d.y() * x * x;
      // W = I + A G with A G = alpha (G - qh (qh^T G)).
      const Eigen::RowVector3d qG = qh_.transpose() * G;
      Mat3 W = alpha_ * (G - qh_ * qG);
      W.diagonal().array() += 1.0;
      double det = 0.0;
      bool invertible = false;
      W.computeInverseAndDetWithCheck(W_inv_, det, invertible, 0.0);
      const double scale = std::abs(W(0, 0) * W(1, 1) * W(2, 2));
      if (invertible && std::isfinite(det) && scale > 0.0 && std::abs(det) > kSingular * scale) {
        woodbury_ = true;
        return;
      }
      assemble(r_, alpha_, qh_);
    }
    if (n_ >= 1) dense_.emplace(M_);
  }
  /// Solves M Z = R for a 6 x n right-hand side (in place).
  template <typename Rhs>
  void solve_in_place(Rhs& R) const {
    if (n_ >= 1 && !woodbury_) {
      dense_->solve_in_place(R);
      return;
    }
    for (int j = 0; j < R.cols(); ++j) {
      const Vec3 u_nu = kn_inv_.cwiseProduct(R.col(j).template head<3>());
      const Vec3 u_om = ko_inv_.cwiseProduct(R.col(j).template tail<3>());
      if (n_ == 0) {
        R.col(j).template head<3>() = u_nu;
        R.col(j).template tail<3>() = u_om;
        continue;
      }
      // w = (I + A G)^-1 A U^T u with U^T u = u_nu + hat(r)^T u_om = u_nu + u_om x r.
      const Vec3 t = u_nu + u_om.cross(r_);
      const Vec3 w = W_inv_ * (alpha_ * (t - qh_ * qh_.dot(t)));
      R.col(j).template head<3>() = u_nu - kn_inv_.cwiseProduct(w);
      R.col(j).template tail<3>() = u_om - ko_inv_.cwiseProduct(r_.cross(w));
    }
  }

 private:
  /// Relative determinant of I + A G below which the dense path is used.
  static constexpr double kSingular = 1e-10;
  void assemble(const Vec3& r, double alpha, const Vec3& qh) {
    if (!assembled_) {
      M_.setZero();
      M_.diagonal().head<3>() = kn_;
      M_.diagonal().tail<3>() = ko_;
      assembled_ = true;
    }
    const Mat3 A = alpha * (Mat3::Identity() - qh * qh.transpose());
    const Mat3 rh = hat(r);
    const Mat3 A_rh = A * rh;
    M_.topLeftCorner<3, 3>() += A;
    M_.topRightCorner<3, 3>() -= A_rh;
    M_.bottomLeftCorner<3, 3>() -= A_rh.transpose();  // hat(r) A = -(A hat(r))^T
    M_.bottomRightCorner<3, 3>() += rh.transpose() * A_rh;  // -hat(r) A hat(r)
  }
  Vec3 kn_, ko_, kn_inv_, ko_inv_;
  int n_ = 0;
  Vec3 r_, qh_;
  double alpha_ = 0.0;
  Mat3 W_inv_;
  bool woodbury_ = false;
  bool assembled_ = false;
  Mat6 M_;
  std::optional<StrainSystem> dense_;
};

}  // namespace

const char* to_string(Summary::Status s) {
  switch (s) {
    case Summary::Status::kConverged: return "converged";
    case Summary::Status::kMaxIterations: return "max_iterations";
    case Summary::Status::kLineSearchFailed: return "line_search_failed";
    case Summary::Status::kSingularJacobian: return "singular_jacobian";
    case Summary::Status::kContinuationFailed: return "continuation_failed";
    case Summary::Status::kInitialPointFailed: return "initial_point_failed";
    case Summary::Status::kNotRun: return "not_run";
  }
  return "unknown";
}

// ---------------------------------------------------------------------------------------
struct ShootingSolver::Impl {
  const rod::RodModel& model;
  Options options;
  // Planar reduction (cosserat/planar.hpp): this Impl solves the reduced problem, with the
  // 3-D Impl `parent` for what is only needed once per solve (the initial guess).
  Impl* parent = nullptr;
  bool planar = false;
  planar::Rod prod;
  int x_tca = 6;  // index of the first TCA unknown: after nu(0), omega(0) (3-D) or their in-plane part
  ode::Integrator integrator;
  std::optional<ode::Integrator> output_integrator;
  std::optional<ode::Integrator> sens_integrator;  // kSensitivity: dimension dim (1 + nx)
  ode::RhsFunction rhs_sens;
  // Coarse RK4 level for cold starts (Options::coarse_steps), and the active level.
  std::optional<ode::Integrator> coarse_integrator, coarse_sens_integrator;
  ode::Integrator* active_plain = nullptr;
  ode::Integrator* active_sens = nullptr;
  // Options::kinematics == kLieGroup: RKMK4 integrators replacing the four above.
  std::optional<LieGroupRk4> lie_plain, lie_sens, lie_coarse_plain, lie_coarse_sens;
  // Cold starts: a middle level with 2 x coarse_steps (when 4 x coarse_steps <= steps); the
  // fine start is the Richardson extrapolation of the coarse and middle solutions.
  std::optional<ode::Integrator> mid_integrator, mid_sens_integrator;
  std::optional<LieGroupRk4> lie_mid_plain, lie_mid_sens;
  LieGroupRk4* active_lie_plain = nullptr;
  LieGroupRk4* active_lie_sens = nullptr;
  Eigen::VectorXd Y;                // augmented state
  // Per actuator, at the last tip residual (TCA drives): the derivatives of the contact
  // residual phi(T, delta) (tca::contact_residual); the TCA row is phi / F_c.
  std::vector<double> dphi_dT;
  std::vector<double> dphi_ddelta;

  int n_act = 0;
  int n_tca = 0;
  int nx = 0;
  // Tip constraint (RodModel::tip_constraint): n_con = 3 (pinned) or 1 (normal only)
  // reaction unknowns at x[k_con...] and as many position residuals at r[k_con...].
  int n_con = 0;
  int k_con = 0;
  Vec3 con_target_W = Vec3::Zero();
  Vec3 con_normal_W = Vec3::Zero();
  int dim = 0;
  double L = 0.0;
  double Fc = 1.0;
  Vec3 K_nu, K_omega, nu_star, omega_star;
  Vec3 K_nu_inv, K_omega_inv;  // reciprocals for StringSystem
  std::vector<int> unknown_of;   // actuator -> unknown index (-1 for tension drives)
  std::vector<int> act_of;       // TCA unknown k (x[6 + k]) -> actuator
  std::vector<double> length_ratio;
  std::vector<double> count;
  std::vector<bool> straight;

  // Current IVP parameters (set before each integration).
  std::vector<double> cT;  // count * tension per actuator
  Vec3 f_ext_W = Vec3::Zero();
  ode::RhsFunction rhs;

  // Work buffers.
  Eigen::VectorXd y;
  Eigen::VectorXd y_acc, x_acc;  // y(L) at the last accepted point x_acc (load fraction 1 only)
  bool acc_full_load = false;
  // IVP memo across solves: y(L) = y_acc is reused when the next IVP has the same initial
  // unknowns, IVP parameters (cT, f_ext) and level, e.g. the first residual of a warm start
  // whose actuation changed only temperatures or tip loads (they enter the tip residual only).
  bool memo_valid = false;
  std::vector<double> acc_cT;
  std::vector<double> acc_dphi_dT, acc_dphi_ddelta;  // at the accepted point (its actuation)
  Eigen::VectorXd coarse_jacobian_x;  // where the last coarse-level Newton Jacobian was taken
  int jacobian_updates = 0;  // Broyden updates of newton()'s Jacobian since it was computed
  Vec3 acc_f_ext = Vec3::Zero();
  const ode::Integrator* acc_level = nullptr;
  std::vector<std::vector<tca::Segment>> scaled_segments;
  int ivp_count = 0;

  Impl(const rod::RodModel& m, const Options& o, Impl* parent_3d = nullptr)
      : model(m),
        options(validated(m, o)),
        parent(parent_3d),
        planar(parent_3d != nullptr),
        integrator(state_dimension(m, parent_3d != nullptr), options.integrator) {
    n_act = static_cast<int>(model.actuators.size());
    dim = state_dimension(model, planar);
    x_tca = planar ? 3 : 6;
    L = model.length_m;
    K_nu = model.shear_extension_stiffness();
    K_omega = model.bending_torsion_stiffness();
    K_nu_inv = K_nu.cwiseInverse();
    K_omega_inv = K_omega.cwiseInverse();
    nu_star = Vec3::UnitZ();
    omega_star = model.reference_curvature_B_1_m;
    // The states and unknowns carry nu - nu* (shooting.hpp), so internal forces keep their
    // digits at any stiffness ratio EA L^2 / EI: no stiffness floor. The tip balance sums
    // the applied forces, so its round-off is eps times the largest of them: F_c is the
    // larger of the bending force scale and the model's own loads.
    Fc = rod::characteristic_force_N(model, rod::Loads::from_model(model));
    unknown_of.assign(n_act, -1);
    for (int i = 0; i < n_act; ++i) {
      const rod::Actuator& a = model.actuators[i];
      if (a.drive.type == rod::Drive::Type::kTca) {
        unknown_of[i] = x_tca + n_tca++;
        act_of.push_back(i);
      }
      length_ratio.push_back(a.rest_length_m / L);
      count.push_back(static_cast<double>(a.count));
      straight.push_back(a.routing.type == rod::Routing::Type::kStraight);
    }
    k_con = x_tca + n_tca;
    if (model.tip_constraint) {
      con_target_W = model.tip_constraint->position_W_m;
      n_con = model.tip_constraint->normal_W ? 1 : 3;
      if (model.tip_constraint->normal_W) con_normal_W = *model.tip_constraint->normal_W;
    }
    nx = x_tca + n_tca + n_con;
    cT.assign(n_act, 0.0);
    if (planar) {
      prod.kn_x = K_nu.x();
      prod.kn_z = K_nu.z();
      prod.kw_y = K_omega.y();
      for (int i = 0; i < n_act; ++i) {
        prod.rho.push_back(model.actuators[i].routing.offset_m.x());
        prod.length_ratio.push_back(length_ratio[i]);
        prod.count.push_back(count[i]);
        prod.direction_of.push_back(unknown_of[i]);
      }
      prod.cT.assign(n_act, 0.0);
    }
    y.resize(dim);
    scaled_segments.resize(n_act);
    if (planar) {
      rhs = [this](double, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
        planar::rhs(prod, yy.data(), dy.data());
      };
    } else {
      rhs = [this](double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) { eval_rhs(s, yy, dy); };
    }
    cache.resize(n_act);
    dphi_dT.assign(n_act, 0.0);
    dphi_ddelta.assign(n_act, 0.0);
    if (options.jacobian == JacobianMethod::kSensitivity && nx > kMaxSensitivityUnknowns) {
      options.jacobian = JacobianMethod::kForwardDifference;
    }
    ode::IntegratorOptions coarse = options.integrator;
    coarse.steps = options.coarse_steps;
    const bool use_coarse = ode::is_fixed_step(options.integrator.method) &&
                            options.coarse_steps > 0 &&
                            2 * options.coarse_steps <= options.integrator.steps;
    if (use_coarse) coarse_integrator.emplace(dim, coarse);
    ode::IntegratorOptions mid = coarse;
    mid.steps = 2 * options.coarse_steps;
    const bool use_mid = use_coarse && 2 * mid.steps <= options.integrator.steps;
    if (use_mid) mid_integrator.emplace(dim, mid);
    if (options.jacobian == JacobianMethod::kSensitivity) {
      sens_integrator.emplace(dim * (1 + nx), options.integrator);
      if (use_coarse) coarse_sens_integrator.emplace(dim * (1 + nx), coarse);
      if (use_mid) mid_sens_integrator.emplace(dim * (1 + nx), mid);
      rhs_ws.resize(6, nx);
      Y.resize(dim * (1 + nx));
      if (planar) {
        rhs_sens = [this](double, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
          planar::rhs_sens(prod, dim, nx, yy.data(), dy.data());
        };
      } else {
        rhs_sens = [this](double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
          eval_rhs_sens(s, yy, dy);
        };
      }
    }
    if (options.kinematics == Kinematics::kLieGroup) {
      lie_plain.emplace(dim, 0, options.integrator.steps);
      if (use_coarse) lie_coarse_plain.emplace(dim, 0, options.coarse_steps);
      if (use_mid) lie_mid_plain.emplace(dim, 0, mid.steps);
      if (options.jacobian == JacobianMethod::kSensitivity) {
        lie_sens.emplace(dim, nx, options.integrator.steps);
        if (use_coarse) lie_coarse_sens.emplace(dim, nx, options.coarse_steps);
        if (use_mid) lie_mid_sens.emplace(dim, nx, mid.steps);
      }

    }
    use_level(false);
  }

  static int state_dimension(const rod::RodModel& m, bool planar_state = false) {
    return (planar_state ? planar::kDelta : kDelta) + static_cast<int>(m.actuators.size());
  }

  /// Whether the model and options admit the planar reduction (cosserat/planar.hpp): straight
  /// strings on the body x axis, reference curvature about y, no tip constraint, a fixed-step
  /// flat integration with sensitivity Jacobians, and at most planar::kMaxActuators actuators
  /// and planar::kMaxDirections unknowns. The actuation is checked per solve (planar_loads).
  static bool planar_model(const rod::RodModel& m, const Options& o) {
    if (!o.planar_reduction || !ode::is_fixed_step(o.integrator.method) ||
        o.kinematics != Kinematics::kFlat || o.jacobian != JacobianMethod::kSensitivity ||
        m.tip_constraint || static_cast<int>(m.actuators.size()) > planar::kMaxActuators) {
      return false;
    }
    if (m.reference_curvature_B_1_m.x() != 0.0 || m.reference_curvature_B_1_m.z() != 0.0) {
      return false;
    }
    int n_tca = 0;
    for (const rod::Actuator& a : m.actuators) {
      if (a.routing.type != rod::Routing::Type::kStraight || a.routing.offset_m.y() != 0.0) {
        return false;
      }
      if (a.drive.type == rod::Drive::Type::kTca) ++n_tca;
    }
    return 3 + n_tca <= planar::kMaxDirections;
  }

  /// Whether the actuation keeps a planar model in its plane: gravity and tip force without
  /// a component along R_WB0 e_y, the tip moment along it only (exact tests).
  bool planar_loads(const Actuation& act) const {
    const Mat3& R0 = model.R_WB0;
    return R0.col(1).dot(act.gravity_W_m_s2) == 0.0 && R0.col(1).dot(act.tip_force_W_N) == 0.0 &&
           R0.col(0).dot(act.tip_moment_W_Nm) == 0.0 && R0.col(2).dot(act.tip_moment_W_Nm) == 0.0;
  }

  static Options validated(const rod::RodModel& m, Options o) {
    require(m.length_m > 0.0 && std::isfinite(m.length_m), "model.length_m", m.length_m,
            "must be > 0");
    require(o.tolerance > 0.0, "options.tolerance", o.tolerance, "must be > 0");
    require(o.coarse_steps >= 0 && o.coarse_steps % 2 == 0, "options.coarse_steps", o.coarse_steps,
            "must be even and >= 0");
    require(o.max_iterations >= 1, "options.max_iterations", o.max_iterations, "must be >= 1");
    require(o.max_line_search_steps >= 1, "options.max_line_search_steps",
            o.max_line_search_steps, "must be >= 1");
    require(o.min_continuation_step > 0.0 && o.min_continuation_step < 1.0,
            "options.min_continuation_step", o.min_continuation_step, "must be in (0, 1)");
    require(o.centerline_intervals >= 0 && o.centerline_intervals % 2 == 0,
            "options.centerline_intervals", o.centerline_intervals,
            "must be even and >= 0 (a sample must lie at L/2)");
    if (ode::is_fixed_step(o.integrator.method)) {
      require(o.integrator.steps % 2 == 0, "options.integrator.steps", o.integrator.steps,
              "must be even (a node must lie at L/2)");
      require(o.centerline_intervals == 0 || o.integrator.steps % o.centerline_intervals == 0,
              "options.centerline_intervals", o.centerline_intervals,
              "must divide options.integrator.steps = " + std::to_string(o.integrator.steps));
    }
    require(o.kinematics == Kinematics::kFlat || o.integrator.method == ode::Method::kRk4,
            "options.integrator.method", "cvode",
            "must be rk4 with options.kinematics = lie_group (a fixed-step method)");
    o.integrator.output_intervals = 0;
    return o;
  }

  // docs/conventions.md "Body-frame ODEs solved by the shooting solver".
  void eval_rhs(double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) const {
    const Eigen::Map<const Mat3> R(yy.data() + kR);
    const Vec3 e = yy.segment<3>(kNu);  // nu - nu* (shooting.hpp layout)
    const Vec3 nu = nu_star + e;
    const Vec3 omega = yy.segment<3>(kOmega);
    // [Pawlowski2019] Eqs. (9)-(10): n_B = K_nu (nu - nu*), m_B = K_omega (omega - omega*).
    const Vec3 n_B = K_nu.cwiseProduct(e);
    const Vec3 m_B = K_omega.cwiseProduct(omega - omega_star);

    // M = K + sum_i U_i A_i U_i^T (StringSystem), A_i = c_i T_i P_i / |q_i|.
    StringSystem M(K_nu, K_omega, K_nu_inv, K_omega_inv);
    // b_nu = -omega x n_B - R^T f_ext - sum g_i;  b_omega = -omega x m_B - nu x n_B - sum r_i x g_i
    Vec3 b_nu = -omega.cross(n_B) - R.transpose() * f_ext_W;
    Vec3 b_omega = -omega.cross(m_B) - nu.cross(n_B);
    for (int i = 0; i < n_act; ++i) {
      const rod::Routing& routing = model.actuators[i].routing;
      Vec3 r, dr, ddr;
      if (straight[i]) {
        r << routing.offset_m.x(), routing.offset_m.y(), 0.0;
        dr.setZero();
        ddr.setZero();
      } else {
        r = routing.r(s);
        dr = routing.dr(s);
        ddr = routing.ddr(s);
      }
      // [Pawlowski2019] Eq. (19): q = nu + omega x r + r'.
      const Vec3 q = nu + omega.cross(r) + dr;
      const double q_norm = q.norm();
      dy[kDelta + i] = q_norm - length_ratio[i];  // delta_i' = |q_i| - L_i
      if (cT[i] == 0.0) continue;
      const Vec3 qh = q / q_norm;
      M.add(r, cT[i] / q_norm, qh);
      // g_i = c_i T_i [omega x qh + P (omega x r' + r'') / |q|],  P v = v - qh (qh . v)
      Vec3 g = omega.cross(qh);
      if (!straight[i]) {
        const Vec3 v = omega.cross(dr) + ddr;
        g += (v - qh * qh.dot(v)) / q_norm;
      }
      g *= cT[i];
      b_nu -= g;
      b_omega -= r.cross(g);
    }
    Vec6 z;
    z << b_nu, b_omega;
    M.factor();
    M.solve_in_place(z);
    // [Pawlowski2019] Eqs. (7)-(8): p' = R nu, R' = R hat(omega).
    dy.segment<3>(kP) = R * nu;
    Eigen::Map<Mat3>(dy.data() + kR) = R * hat(omega);
    dy.segment<6>(kNu) = z;
    dy.segment<3>(kC) = yy.segment<3>(kP);  // c' = p
  }

  /// Per-actuator quantities shared by the state and sensitivity parts of the RHS.
  struct ActuatorCache {
    Vec3 r, dr, qh, v, Pv, gb, Pw;
    double q_norm = 1.0;
  };
  mutable std::vector<ActuatorCache> cache;
  mutable Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxSensitivityUnknowns> rhs_ws;  // 6 x nx

  /// RHS of the state and of its forward sensitivities Y_j = dy/dx_j (the variational
  /// equations Y_j' = (df/dy) Y_j + df/dx_j, x_j = T_k entering through c_k T_k). Layout:
  /// Y = (y, Y_0, ..., Y_{nx-1}), each block of length `dim`. The directional derivative
  /// of the linear system M z = b is dz = M^-1 (db - dM z), with the same LU as z.
  void eval_rhs_sens(double s, const Eigen::VectorXd& Ya, Eigen::VectorXd& dY) const {
    const double* yy = Ya.data();
    const Eigen::Map<const Mat3> R(yy + kR);
    const Vec3 e(yy + kNu);  // nu - nu*
    const Vec3 nu = nu_star + e;
    const Vec3 omega(yy + kOmega);
    const Vec3 n_B = K_nu.cwiseProduct(e);
    const Vec3 m_B = K_omega.cwiseProduct(omega - omega_star);
    StringSystem lu(K_nu, K_omega, K_nu_inv, K_omega_inv);
    Vec3 b_nu = -omega.cross(n_B) - R.transpose() * f_ext_W;
    Vec3 b_omega = -omega.cross(m_B) - nu.cross(n_B);
    for (int i = 0; i < n_act; ++i) {
      ActuatorCache& c = cache[i];
      const rod::Routing& routing = model.actuators[i].routing;
      Vec3 ddr;
      if (straight[i]) {
        c.r << routing.offset_m.x(), routing.offset_m.y(), 0.0;
        c.dr.setZero();
        ddr.setZero();
      } else {
        c.r = routing.r(s);
        c.dr = routing.dr(s);
        ddr = routing.ddr(s);
      }
      const Vec3 q = nu + omega.cross(c.r) + c.dr;
      c.q_norm = q.norm();
      c.qh = q / c.q_norm;
      dY[kDelta + i] = c.q_norm - length_ratio[i];
      c.v = omega.cross(c.dr) + ddr;
      c.Pv = c.v - c.qh * c.qh.dot(c.v);
      c.gb = omega.cross(c.qh) + c.Pv / c.q_norm;  // g_i = c_i T_i gb_i
      if (cT[i] == 0.0) continue;
      lu.add(c.r, cT[i] / c.q_norm, c.qh);
      const Vec3 g = cT[i] * c.gb;
      b_nu -= g;
      b_omega -= c.r.cross(g);
    }
    Vec6 z;
    z << b_nu, b_omega;
    lu.factor();
    lu.solve_in_place(z);
    dY.segment<3>(kP) = R * nu;
    Eigen::Map<Mat3>(dY.data() + kR) = R * hat(omega);
    dY.segment<6>(kNu) = z;
    dY.segment<3>(kC) = Ya.segment<3>(kP);
    const Vec3 zn = z.head<3>(), zo = z.tail<3>();
    for (int i = 0; i < n_act; ++i) {
      ActuatorCache& c = cache[i];
      const Vec3 w = zn - c.r.cross(zo);  // M z = K z + sum [A_i w_i; r_i x A_i w_i]
      c.Pw = w - c.qh * c.qh.dot(w);
    }
    // Right-hand sides db_j - dM_j z of all directions, solved together.
    auto& B = rhs_ws;
    for (int j = 0; j < nx; ++j) {
      const double* yj = yy + dim * (j + 1);
      double* dyj = dY.data() + dim * (j + 1);
      const Eigen::Map<const Mat3> dR(yj + kR);
      const Vec3 dnu(yj + kNu), dom(yj + kOmega);
      const Vec3 dn_B = K_nu.cwiseProduct(dnu), dm_B = K_omega.cwiseProduct(dom);
      Vec3 db_nu = -dom.cross(n_B) - omega.cross(dn_B) - dR.transpose() * f_ext_W;
      Vec3 db_om = -dom.cross(m_B) - omega.cross(dm_B) - dnu.cross(n_B) - nu.cross(dn_B);
      for (int i = 0; i < n_act; ++i) {
        const ActuatorCache& c = cache[i];
        const Vec3 dq = dnu + dom.cross(c.r);
        const double dqn = c.qh.dot(dq);
        dyj[kDelta + i] = dqn;
        const double dcT = unknown_of[i] == j ? count[i] : 0.0;
        if (cT[i] == 0.0 && dcT == 0.0) continue;
        const Vec3 dqh = (dq - c.qh * dqn) / c.q_norm;
        // dP u = -(dqh (qh . u) + qh (dqh . u))
        const Vec3 dv = dom.cross(c.dr);
        const Vec3 dPv = -(dqh * c.qh.dot(c.v) + c.qh * dqh.dot(c.v));
        const Vec3 Pdv = dv - c.qh * c.qh.dot(dv);
        const Vec3 dgb = dom.cross(c.qh) + omega.cross(dqh) + (dPv + Pdv) / c.q_norm -
                         c.Pv * (dqn / (c.q_norm * c.q_norm));
        const Vec3 dg = dcT * c.gb + cT[i] * dgb;
        // d(A w) with w fixed: A = c T P / |q|
        const Vec3 w = zn - c.r.cross(zo);
        const Vec3 dPw = -(dqh * c.qh.dot(w) + c.qh * dqh.dot(w));
        const Vec3 dAw = (dcT * c.Pw + cT[i] * dPw) / c.q_norm -
                         c.Pw * (cT[i] * dqn / (c.q_norm * c.q_norm));
        db_nu -= dg + dAw;
        db_om -= c.r.cross(dg + dAw);
      }
      B.col(j) << db_nu, db_om;
      Eigen::Map<Vec3>(dyj + kP) = dR * nu + R * dnu;
      Eigen::Map<Mat3>(dyj + kR) = dR * hat(omega) + R * hat(dom);
      Eigen::Map<Vec3>(dyj + kC) = Vec3(yj + kP);
    }
    lu.solve_in_place(B);
    for (int j = 0; j < nx; ++j) Eigen::Map<Vec6>(dY.data() + dim * (j + 1) + kNu) = B.col(j);
  }

  /// Sets cT and f_ext for load fraction lambda and unknowns x; fills scaled segments.
  void set_parameters(const Actuation& act, double lambda, const Eigen::VectorXd& x) {
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      const double T = k >= 0 ? x[k] : lambda * act.actuators[i].tension_N;
      cT[i] = count[i] * T;
      if (k >= 0) {
        const auto& tca = *model.actuators[i].drive.tca;
        const double t_ref = tca.material().reference_temperature_K;
        auto& segs = scaled_segments[i];
        segs = act.actuators[i].segments;  // no allocation after the first call
        for (tca::Segment& seg : segs) seg.temperature_K = t_ref + lambda * (seg.temperature_K - t_ref);
      }
    }
    f_ext_W = lambda * model.material.density_kg_m3 * model.section.area_m2 * act.gravity_W_m_s2;
    if (planar) {
      prod.cT = cT;
      const Vec3 f_B0 = model.R_WB0.transpose() * f_ext_W;
      prod.f_x = f_B0.x();
      prod.f_z = f_B0.z();
    }
  }

  void initial_state(const Eigen::VectorXd& x, Eigen::VectorXd& y0) const {
    y0.setZero();
    if (planar) {
      y0[planar::kCS] = 1.0;  // Rot_y(0) = I
      y0.segment<3>(planar::kNu) = x.head<3>();  // (nu_x, nu_z - 1, kappa) are contiguous
      return;
    }
    y0.segment<3>(kP) = model.base_position_W_m;
    Eigen::Map<Mat3>(y0.data() + kR) = model.R_WB0;
    y0.segment<3>(kNu) = x.head<3>();
    y0.segment<3>(kOmega) = x.segment<3>(3);
  }

  /// Scaled residual at x; y(L) left in `y`. False when the IVP or a TCA law fails.
  bool residual(const Actuation& act, double lambda, const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    if (!all_finite(x)) return false;
    set_parameters(act, lambda, x);
    if (memo_valid && acc_level == active_plain && x_acc.size() == x.size() && x_acc == x &&
        acc_cT == cT && acc_f_ext == f_ext_W) {
      y = y_acc;  // same IVP as the last accepted one: no integration
      return tip_residual(act, lambda, x, y, r);
    }
    initial_state(x, y);
    ++ivp_count;
    if (active_lie_plain) {
      if (!active_lie_plain->integrate(rhs, 0.0, L, y) || !all_finite(y)) return false;
      return tip_residual(act, lambda, x, y, r);
    }
    const ode::IntegrationSummary is = active_plain->integrate(rhs, 0.0, L, y);
    if (is.status != ode::IntegrationSummary::Status::kSuccess || !all_finite(y)) return false;
    return tip_residual(act, lambda, x, y, r);
  }

  /// Residual and its exact Jacobian from one augmented IVP (kSensitivity).
  bool residual_and_jacobian(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                             Eigen::VectorXd& r, Eigen::MatrixXd& J) {
    if (!all_finite(x)) return false;
    set_parameters(act, lambda, x);
    Y.setZero();
    initial_state(x, y);
    Y.head(dim) = y;
    // d y(0) / d (nu0, omega0) (planar: d y(0) / d (nu_x0, nu_z0, kappa0))
    for (int j = 0; j < x_tca; ++j) Y[dim * (j + 1) + (planar ? planar::kNu : kNu) + j] = 1.0;
    ++ivp_count;
    if (active_lie_sens) {
      if (!active_lie_sens->integrate(rhs_sens, 0.0, L, Y) || !all_finite(Y)) return false;
    } else {
      const ode::IntegrationSummary is = active_sens->integrate(rhs_sens, 0.0, L, Y);
      if (is.status != ode::IntegrationSummary::Status::kSuccess || !all_finite(Y)) return false;
    }
    y = Y.head(dim);
    if (!tip_residual(act, lambda, x, y, r)) return false;
    J.resize(nx, nx);
    if (planar) return planar_jacobian(act, lambda, J);
    // Chain rule through the tip conditions: dr = (dr/dy) Y(L) + dr/dT.
    const Eigen::Map<const Mat3> R(y.data() + kR);
    const Vec3 nu = nu_star + y.segment<3>(kNu), omega = y.segment<3>(kOmega);
    const Vec3 F_e = lambda * act.tip_force_W_N + reaction_W(x), M_e = lambda * act.tip_moment_W_Nm;
    for (int j = 0; j < nx; ++j) {
      const double* yj = Y.data() + dim * (j + 1);
      const Eigen::Map<const Mat3> dR(yj + kR);
      const Vec3 dnu(yj + kNu), dom(yj + kOmega);
      Vec3 drn = K_nu.cwiseProduct(dnu) - dR.transpose() * F_e;
      Vec3 drm = K_omega.cwiseProduct(dom) - dR.transpose() * M_e;
      for (int i = 0; i < n_act; ++i) {
        const double dcT = unknown_of[i] == j ? count[i] : 0.0;
        if (cT[i] == 0.0 && dcT == 0.0) continue;
        const rod::Routing& ro = model.actuators[i].routing;
        const Vec3 ri = ro.r(L);
        const Vec3 q = nu + omega.cross(ri) + ro.dr(L);
        const double qn = q.norm();
        const Vec3 qh = q / qn;
        const Vec3 dq = dnu + dom.cross(ri);
        const Vec3 dqh = (dq - qh * qh.dot(dq)) / qn;
        const Vec3 dF = dcT * qh + cT[i] * dqh;
        drn += dF;
        drm += ri.cross(dF);
      }
      // A reaction unknown enters only the tip force (its IVP sensitivity is zero).
      if (j >= k_con) drn -= R.transpose() * (n_con == 3 ? Vec3::Unit(j - k_con) : con_normal_W);
      J.block<3, 1>(0, j) = drn / Fc;
      J.block<3, 1>(3, j) = drm / (Fc * L);
      for (int i = 0; i < n_act; ++i) {
        const int k = unknown_of[i];
        if (k < 0) continue;
        J(k, j) = ((k == j ? dphi_dT[i] : 0.0) + dphi_ddelta[i] * yj[kDelta + i]) / Fc;
      }
      if (n_con == 3) J.block<3, 1>(k_con, j) = Vec3(yj + kP) / L;
      if (n_con == 1) J(k_con, j) = con_normal_W.dot(Vec3(yj + kP)) / L;
    }
    return J.allFinite();
  }

  /// Planar reduction: the Jacobian of the scaled residual from the sensitivities in Y (the
  /// tip wrench rows by planar::tip_wrench_sens, the TCA rows by the chain rule).
  bool planar_jacobian(const Actuation& act, double lambda, Eigen::MatrixXd& J) const {
    const Vec3 F_B0 = model.R_WB0.transpose() * (lambda * act.tip_force_W_N);
    double dw[3 * planar::kMaxDirections];
    planar::tip_wrench_sens(prod, F_B0.x(), F_B0.z(), dim, nx, Y.data(), dw);
    for (int j = 0; j < nx; ++j) {
      J(0, j) = dw[3 * j] / Fc;
      J(1, j) = dw[3 * j + 1] / Fc;
      J(2, j) = dw[3 * j + 2] / (Fc * L);
      const double* yj = Y.data() + dim * (j + 1);
      for (int i = 0; i < n_act; ++i) {
        const int k = unknown_of[i];
        if (k >= 0) J(k, j) = ((k == j ? dphi_dT[i] : 0.0) + dphi_ddelta[i] * yj[planar::kDelta + i]) / Fc;
      }
    }
    return J.allFinite();
  }

  // docs/conventions.md "Tip conditions" (body frame), scaled.
  bool tip_residual(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& yL, Eigen::VectorXd& r) {
    r.resize(nx);
    if (planar) {
      // The in-plane rows (force x, z; moment y) of the 3-D residual; the others are zero.
      const Vec3 F_B0 = model.R_WB0.transpose() * (lambda * act.tip_force_W_N);
      const double M_y = model.R_WB0.col(1).dot(lambda * act.tip_moment_W_Nm);
      double w[3];
      planar::tip_wrench(prod, omega_star.y(), F_B0.x(), F_B0.z(), M_y, yL.data(), w);
      r[0] = w[0] / Fc;
      r[1] = w[1] / Fc;
      r[2] = w[2] / (Fc * L);
      return tca_rows(x, yL, planar::kDelta, r);
    }
    const Eigen::Map<const Mat3> R(yL.data() + kR);
    const Vec3 e = yL.segment<3>(kNu);  // nu - nu*
    const Vec3 nu = nu_star + e;
    const Vec3 omega = yL.segment<3>(kOmega);
    // The holder's reaction (an unknown, not scaled by lambda) adds to the applied tip force.
    Vec3 rn = K_nu.cwiseProduct(e) -
              R.transpose() * (lambda * act.tip_force_W_N + reaction_W(x));
    Vec3 rm = K_omega.cwiseProduct(omega - omega_star) - R.transpose() * (lambda * act.tip_moment_W_Nm);
    for (int i = 0; i < n_act; ++i) {
      if (cT[i] == 0.0) continue;
      const Vec3 ri = model.actuators[i].routing.r(L);
      const Vec3 q = nu + omega.cross(ri) + model.actuators[i].routing.dr(L);
      const Vec3 qh = q.normalized();
      rn += cT[i] * qh;
      rm += cT[i] * ri.cross(qh);
    }
    r.head<3>() = rn / Fc;
    r.segment<3>(3) = rm / (Fc * L);
    // Tip constraint: position error (pinned) or its normal component, scaled by L.
    if (n_con == 3) r.segment<3>(k_con) = (yL.segment<3>(kP) - con_target_W) / L;
    if (n_con == 1) r[k_con] = con_normal_W.dot(yL.segment<3>(kP) - con_target_W) / L;
    return tca_rows(x, yL, kDelta, r);
  }

  /// TCA rows r_k = phi(T_k, delta_k(L)) / F_c (tca::contact_residual: the free-coil law
  /// T_k - F_tca(delta_k) with coil contact) with delta at yL[delta0 + i]; sets dphi_dT and
  /// dphi_ddelta. False when a TCA law fails or r is not finite.
  bool tca_rows(const Eigen::VectorXd& x, const Eigen::VectorXd& yL, int delta0, Eigen::VectorXd& r) {
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      if (k < 0) continue;
      try {
        const tca::ContactResidual c = tca::contact_residual(
            *model.actuators[i].drive.tca, x[k], yL[delta0 + i], scaled_segments[i]);
        r[k] = c.phi_N / Fc;
        dphi_dT[i] = c.dphi_dF;
        dphi_ddelta[i] = c.dphi_ddelta_N_m;
      } catch (const DomainError&) {
        return false;
      }
    }
    return all_finite(r);
  }

  /// Tip force the holder applies to the rod (world frame) for unknowns x; 0 without a
  /// tip constraint.
  Vec3 reaction_W(const Eigen::VectorXd& x) const {
    if (n_con == 3) return x.segment<3>(k_con);
    if (n_con == 1) return x[k_con] * con_normal_W;
    return Vec3::Zero();
  }

  Eigen::VectorXd typical_scale() const {
    assert(!planar && "the planar reduction uses sensitivity Jacobians, never differences");
    Eigen::VectorXd t(nx);
    t.head<3>() = Fc * K_nu_inv;  // the strain deviation of the characteristic force
    t.segment<3>(3).setConstant(1.0 / L);
    t.segment(6, n_tca).setConstant(Fc);
    t.tail(n_con).setConstant(Fc);
    return t;
  }

  bool fd_jacobian(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& r0, Eigen::MatrixXd& J) {
    J.resize(nx, nx);
    const Eigen::VectorXd typ = typical_scale();
    Eigen::VectorXd xp = x, rp(nx), rm(nx);
    const bool central = options.jacobian == JacobianMethod::kCentralDifference;
    for (int j = 0; j < nx; ++j) {
      const double base = std::max(std::abs(x[j]), typ[j]);
      double h = (central ? kCentralStep : kForwardStep) * base;
      const double xj = x[j];
      xp[j] = xj + h;
      h = xp[j] - xj;  // exactly representable step
      if (!residual(act, lambda, xp, rp)) { xp[j] = xj; return false; }
      if (central) {
        xp[j] = xj - h;
        if (!residual(act, lambda, xp, rm)) { xp[j] = xj; return false; }
        J.col(j) = (rp - rm) / (2.0 * h);
      } else {
        J.col(j) = (rp - r0) / h;
      }
      xp[j] = xj;
    }
    return J.allFinite();
  }

  /// Constant strains of the closed form (docs/conventions.md) for tensions cT (count x
  /// tension per actuator), offsets taken at s = 0: e = nu - nu* (the deviation, no
  /// cancellation) and omega (the reference curvature plus the deviation).
  void closed_form_strains(const std::vector<double>& cTs, Vec3& e, Vec3& omega) const {
    double sum_T = 0.0, sum_Tx = 0.0, sum_Ty = 0.0;
    for (int i = 0; i < n_act; ++i) {
      const Vec3 r = model.actuators[i].routing.r(0.0);
      sum_T += cTs[i];
      sum_Tx += cTs[i] * r.x();
      sum_Ty += cTs[i] * r.y();
    }
    e = Vec3(0.0, 0.0, -sum_T / K_nu.z());
    omega = omega_star + Vec3(-sum_Ty / K_omega.x(), sum_Tx / K_omega.y(), 0.0);
  }

  /// Pose at arc length s of a rod with constant strains (nu, omega) from the base pose:
  /// R = R0 exp(s hat(omega)), p = p0 + R0 V nu with V = int_0^s exp(t hat(omega)) dt.
  void arc_pose(const Vec3& nu, const Vec3& omega, double s, Mat3& R, Vec3& p) const {
    const Vec3 a = s * omega;
    const double th = a.norm();
    const Mat3 A = hat(a), A2 = A * A;
    double c1, c2, c3;  // sin(th)/th, (1 - cos th)/th^2, (th - sin th)/th^3
    if (th < 1e-4) {
      c1 = 1.0 - th * th / 6.0;
      c2 = 0.5 - th * th / 24.0;
      c3 = 1.0 / 6.0 - th * th / 120.0;
    } else {
      c1 = std::sin(th) / th;
      c2 = (1.0 - std::cos(th)) / (th * th);
      c3 = (th - std::sin(th)) / (th * th * th);
    }
    R = model.R_WB0 * (Mat3::Identity() + c1 * A + c2 * A2);
    p = model.base_position_W_m + model.R_WB0 * (s * (nu + c2 * (A * nu) + c3 * (A2 * nu)));
  }

  /// Strains the distributed load f_ext_W (gravity) adds to a rod bent with constant strains
  /// (nu, omega): K^-1 R(s)^T times the internal force and moment the load beyond s requires
  /// (docs/conventions.md "Global equilibrium"), on kGuessNodes + 1 nodes; returns their mean
  /// over s and their value at s = 0.
  void load_strains(const Vec3& nu, const Vec3& omega, Vec6& mean, Vec6& base) const {
    constexpr int N = kGuessNodes;
    std::array<Mat3, N + 1> R;
    std::array<Vec3, N + 1> p;
    for (int k = 0; k <= N; ++k) arc_pose(nu, omega, L * k / N, R[k], p[k]);
    const double h = L / N;
    mean.setZero();
    Vec3 c_tail = Vec3::Zero();  // int_s^L p, trapezoidal rule, accumulated from the tip
    for (int k = N; k >= 0; --k) {
      if (k < N) c_tail += 0.5 * h * (p[k] + p[k + 1]);
      const double tail = L - k * h;
      const Vec3 n = tail * f_ext_W;
      const Vec3 m = (c_tail - tail * p[k]).cross(f_ext_W);
      Vec6 d;
      d << K_nu_inv.cwiseProduct(R[k].transpose() * n), K_omega_inv.cwiseProduct(R[k].transpose() * m);
      mean += (k == 0 || k == N ? 0.5 : 1.0) / N * d;
      if (k == 0) base = d;
    }
  }

  /// Initial guess (docs/conventions.md "Initial guess"): the closed-form constant-strain rod
  /// of the known tensions and of the TCA tensions solving T_k = F_tca(delta_k(T)) with the
  /// closed-form elongations (a small Newton iteration; T_tca = 0 if it fails), plus, if
  /// `with_gravity`, the strains of gravity on that bent rod: a fixed-point iteration bends
  /// the arc by their mean and the unknowns take their value at the base. Without a converged
  /// fixed point gravity is ignored; *used_gravity tells whether it was included. Tip loads
  /// are ignored (large ones, e.g. a holder's reaction, admit other equilibria).
  Eigen::VectorXd initial_guess(const Actuation& act, double lambda, bool with_gravity,
                                 bool* used_gravity = nullptr) {
    if (planar) {
      // The 3-D guess of a planar problem lies in the plane (its other components are
      // exact zeros): keep its in-plane unknowns.
      return reduce(parent->initial_guess(act, lambda, with_gravity, used_gravity));
    }
    if (used_gravity) *used_gravity = false;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(nx);
    set_parameters(act, lambda, x);  // cT of the known tensions, scaled TCA segments
    std::vector<double> cTs = cT;
    Vec3 e, omega;  // e = nu - nu*
    if (with_gravity && !f_ext_W.isZero(0.0)) {
      Vec6 mean = Vec6::Zero();
      for (int it = 0; it < kGuessIterations; ++it) {
        guess_tensions(mean, cTs, x);
        closed_form_strains(cTs, e, omega);
        Vec6 next_mean, base;
        load_strains(nu_star + e + mean.head<3>(), omega + mean.tail<3>(), next_mean, base);
        if (!next_mean.allFinite() || !base.allFinite()) break;
        const double change = (next_mean - mean).lpNorm<Eigen::Infinity>();
        mean = next_mean;
        if (change <= kGuessTolerance * (1.0 / L + mean.lpNorm<Eigen::Infinity>())) {
          guess_tensions(mean, cTs, x);
          closed_form_strains(cTs, e, omega);
          x.head<3>() = e + base.head<3>();
          x.segment<3>(3) = omega + base.tail<3>();
          if (used_gravity) *used_gravity = true;
          return x;
        }
      }
    }
    guess_tensions(Vec6::Zero(), cTs, x);  // without gravity (none, or no fixed point)
    closed_form_strains(cTs, e, omega);
    x.head<3>() = e;
    x.segment<3>(3) = omega;
    return x;
  }

  /// TCA tensions of the guess: T_k = F_tca(delta_k(T)) with delta_k of the closed-form
  /// strains plus `extra` (the mean load strains), by a small damped Newton iteration
  /// (dT/d delta from the closed form); sets x's TCA entries (0 if it fails) and their
  /// c T in cTs (known tensions as set by set_parameters).
  void guess_tensions(const Vec6& extra, std::vector<double>& cTs, Eigen::VectorXd& x) {
    if (n_tca == 0) return;
    Vec3 nu, omega;
    Eigen::VectorXd T = Eigen::VectorXd::Zero(n_tca), g(n_tca), dT(n_tca);
    Eigen::MatrixXd G(n_tca, n_tca);
    // Residuals g_k = phi_k(T_k, delta_k(T)) of the closed-form model (the TCA law with coil
    // contact, tca::contact_residual); it may throw.
    auto eval = [&](const Eigen::VectorXd& Tk, Eigen::VectorXd& gk, Eigen::MatrixXd* Gk) {
      for (int k = 0; k < n_tca; ++k) cTs[act_of[k]] = count[act_of[k]] * Tk[k];
      closed_form_strains(cTs, nu, omega);
      nu += nu_star + extra.head<3>();
      omega += extra.tail<3>();
      for (int k = 0; k < n_tca; ++k) {
        const int i = act_of[k];
        const rod::Routing& ro = model.actuators[i].routing;
        const double delta =
            L * (nu + omega.cross(ro.r(0.0)) + ro.dr(0.0)).norm() - model.actuators[i].rest_length_m;
        const tca::ContactResidual c =
            tca::contact_residual(*model.actuators[i].drive.tca, Tk[k], delta, scaled_segments[i]);
        gk[k] = c.phi_N;
        if (Gk) {
          const Vec3 ri = ro.r(0.0);
          for (int l = 0; l < n_tca; ++l) {
            const Vec3 rl = model.actuators[act_of[l]].routing.r(0.0);
            // d delta_k / d T_l = -L C_kl c_l (closed form)
            const double C = 1.0 / K_nu.z() + ri.y() * rl.y() / K_omega.x() +
                             ri.x() * rl.x() / K_omega.y();
            (*Gk)(k, l) = (k == l ? c.dphi_dF : 0.0) - c.dphi_ddelta_N_m * L * C * count[act_of[l]];
          }
        }
      }
      return gk.allFinite();
    };
    bool ok = false;
    try {
      ok = eval(T, g, &G);
      for (int it = 0; ok && it < 30 && g.lpNorm<Eigen::Infinity>() > 1e-12 * Fc; ++it) {
        dT = G.partialPivLu().solve(-g);
        double t = 1.0;
        Eigen::VectorXd Tt(n_tca), gt(n_tca);
        bool accepted = false;
        for (int ls = 0; ls < 30 && !accepted; ++ls, t *= 0.5) {
          Tt = T + t * dT;
          try {
            accepted = eval(Tt, gt, nullptr) && gt.squaredNorm() < g.squaredNorm();
          } catch (const DomainError&) {
            accepted = false;
          }
        }
        if (!accepted) break;
        T = Tt;
        ok = eval(T, g, &G);
      }
    } catch (const DomainError&) {
      ok = false;
    }
    if (ok && T.allFinite()) {
      x.segment(6, n_tca) = T;
    } else {
      x.segment(6, n_tca).setZero();
    }
    for (int k = 0; k < n_tca; ++k) cTs[act_of[k]] = count[act_of[k]] * x[6 + k];
  }

  /// Damped Newton at load fraction lambda: the Jacobian (sensitivities or differences) is
  /// computed at x when missing; after an accepted step it is Broyden-updated (trial points
  /// cost one plain IVP) unless the step reduced ||r|| by less than kBroydenMinReduction
  /// (then it is recomputed at the new point); a stale Jacobian gets kStaleLineSearchSteps
  /// halvings before it is recomputed. x and J are in/out (J.size() == 0: no Jacobian yet).
  Summary::Status newton(const Actuation& act, double lambda, Eigen::VectorXd& x,
                         Eigen::MatrixXd& J, Summary& summary, std::string& why,
                         double tolerance) {
    Eigen::VectorXd r(nx), xt(nx), rt(nx), dx(nx);
    if (!residual(act, lambda, x, r)) {
      why = "the IVP or a TCA law failed at the initial guess";
      return Summary::Status::kInitialPointFailed;
    }
    remember(lambda, x);
    bool fresh = false;
    if (J.rows() != nx || J.cols() != nx) J.resize(0, 0);
    for (int it = 0;; ++it) {
      summary.residual = r.lpNorm<Eigen::Infinity>();
      if (summary.residual <= tolerance) return Summary::Status::kConverged;
      if (it >= options.max_iterations) {
        why = "reached max_iterations = " + std::to_string(options.max_iterations) +
              " with scaled residual " + format_value(summary.residual);
        return Summary::Status::kMaxIterations;
      }
      if (J.size() == 0) {
        bool approximate = false;
        const bool ok = options.jacobian == JacobianMethod::kSensitivity
                            ? newton_jacobian(act, lambda, x, r, J, approximate)
                            : fd_jacobian(act, lambda, x, r, J);
        if (!ok) {
          why = "Jacobian evaluation failed (non-finite IVP)";
          J.resize(0, 0);
          return Summary::Status::kLineSearchFailed;
        }
        fresh = !approximate;  // a coarse-level Jacobian is treated like a stale one
        jacobian_updates = 0;
      }
      dx = J.partialPivLu().solve(-r);
      if (!dx.allFinite()) {
        if (!fresh) { J.resize(0, 0); --it; continue; }
        why = "singular shooting Jacobian";
        return Summary::Status::kSingularJacobian;
      }
      const double phi = 0.5 * r.squaredNorm();
      double t = 1.0;
      bool accepted = false;
      const int max_ls = fresh ? options.max_line_search_steps : kStaleLineSearchSteps;
      for (int ls = 0; ls < max_ls; ++ls, t *= 0.5) {
        xt = x + t * dx;
        if (residual(act, lambda, xt, rt) &&
            0.5 * rt.squaredNorm() <= (1.0 - 2.0 * kArmijo * t) * phi) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        if (!fresh) { J.resize(0, 0); --it; continue; }  // retry with a fresh FD Jacobian
        why = "line search found no decrease of ||r||^2 along the Newton direction";
        return Summary::Status::kLineSearchFailed;
      }
      ++summary.iterations;
      const bool poor = rt.norm() > kBroydenMinReduction * r.norm();
      // A poor step with a fresh Jacobian: the map is far from linear here. Sensitivities
      // are cheap enough to recompute; an FD Jacobian (nx IVPs) is Broyden-updated instead.
      const bool fd = options.jacobian != JacobianMethod::kSensitivity;
      if (options.broyden_updates && (!poor || (fresh && fd))) {
        // Broyden's "good" update: J += (dr - J s) s^T / (s^T s).
        const Eigen::VectorXd s = xt - x;
        const double ss = s.squaredNorm();
        if (ss > 0.0) J.noalias() += ((rt - r) - J * s) * (s.transpose() / ss);
        fresh = false;
        ++jacobian_updates;
      } else {
        J.resize(0, 0);
      }
      x = xt;
      r = rt;
      remember(lambda, x);
    }
  }

  /// Sensitivity Jacobian for Newton at x (r: the residual at x, kept). On the fine level
  /// with a coarse level (Options::coarse_steps), the first request at a point uses the coarse
  /// level's sensitivities (coarse_steps / steps of the cost; within the coarse discretization
  /// error of the fine Jacobian) and sets `approximate`; a second request at the same point
  /// (the approximate one failed) computes the fine Jacobian.
  bool newton_jacobian(const Actuation& act, double lambda, const Eigen::VectorXd& x,
                       Eigen::VectorXd& r, Eigen::MatrixXd& J, bool& approximate) {
    approximate = false;
    const bool fine = active_plain == &integrator;
    if (!fine || !coarse_sens_integrator || (coarse_jacobian_x.size() == x.size() && coarse_jacobian_x == x)) {
      return residual_and_jacobian(act, lambda, x, r, J);
    }
    coarse_jacobian_x = x;
    Eigen::VectorXd rc;
    use_level(true);
    const bool ok = residual_and_jacobian(act, lambda, x, rc, J);
    use_level(false);
    if (!ok) return residual_and_jacobian(act, lambda, x, r, J);
    approximate = true;
    return true;
  }

  /// Cold start: converges the middle level (2 N_c steps) from the coarse solution xc and
  /// starts the fine level (N_f steps) at the Richardson extrapolation of the two, which
  /// removes the leading O(h^p) term (p: the method's order, 4, 6 or 8) of the discretization
  /// error of x:
  ///   x(N) = x* + C N^-p  =>  x(N_f) = x_m + (x_m - x_c) (N_f^-p - N_m^-p) / (N_m^-p - N_c^-p).
  /// On failure x, J keep the coarse solution.
  void cold_extrapolation(const Actuation& act, const Eigen::VectorXd& xc, const Eigen::MatrixXd& Jc,
                          Eigen::VectorXd& x, Eigen::MatrixXd& J, Summary& summary) {
    Eigen::VectorXd xm = xc;
    Eigen::MatrixXd Jm = Jc;
    std::string why;
    use_mid_level();
    const Summary::Status sm = newton(act, 1.0, xm, Jm, summary, why, kCoarseTolerance);
    use_level(false);
    if (sm != Summary::Status::kConverged) return;
    const double p = ode::order_of(options.integrator.method);
    const double a = std::pow(static_cast<double>(options.coarse_steps), -p);
    const double b = std::pow(2.0 * options.coarse_steps, -p);
    const double c = std::pow(static_cast<double>(options.integrator.steps), -p);
    x = xm + ((c - b) / (b - a)) * (xm - xc);
    J = jacobian_updates <= kMaxHandedOverUpdates ? Jm : Eigen::MatrixXd();
  }

  /// Selects the middle level (2 x coarse_steps); use_level(false) returns to the fine one.
  void use_mid_level() {
    active_plain = &*mid_integrator;
    active_sens = mid_sens_integrator ? &*mid_sens_integrator : nullptr;
    active_lie_plain = lie_mid_plain ? &*lie_mid_plain : nullptr;
    active_lie_sens = lie_mid_sens ? &*lie_mid_sens : nullptr;
  }

  /// Selects the coarse or the fine (Options::integrator) IVP level.
  void use_level(bool coarse) {
    active_plain = coarse ? &*coarse_integrator : &integrator;
    active_lie_plain = lie_plain ? (coarse ? &*lie_coarse_plain : &*lie_plain) : nullptr;
    active_lie_sens = lie_sens ? (coarse ? &*lie_coarse_sens : &*lie_sens) : nullptr;
    active_sens = sens_integrator ? (coarse ? &*coarse_sens_integrator : &*sens_integrator) : nullptr;
  }

  /// Warm start: the actuation change (temperatures) alters the TCA rows of the Jacobian
  /// only through the contact residual's derivatives (the IVP does not depend on
  /// temperatures). Row k is (a e_k + b ddelta/dx) / F_c with a = dphi/dT_k, b = dphi/d delta,
  /// so it is rebuilt from the previous solution's (a, b) and the new ones at the same point
  /// under `act` (the residual there comes from the IVP memo, without integration).
  void refresh_tca_rows(const Actuation& act, const Eigen::VectorXd& x, Eigen::MatrixXd& J) {
    if (n_tca == 0 || !memo_valid || x_acc.size() != x.size() || x_acc != x) return;
    const std::vector<double> a_old = acc_dphi_dT, b_old = acc_dphi_ddelta;
    Eigen::VectorXd r;
    if (!residual(act, 1.0, x, r)) return;
    remember(1.0, x);  // Newton's first residual at x is then answered by the memo too
    for (int i = 0; i < n_act; ++i) {
      const int k = unknown_of[i];
      if (k < 0 || b_old[i] == 0.0 || !std::isfinite(dphi_ddelta[i])) continue;
      J(k, k) -= a_old[i] / Fc;
      J.row(k) *= dphi_ddelta[i] / b_old[i];
      J(k, k) += dphi_dT[i] / Fc;
    }
  }

  /// The actuation as a flat vector (documented at ShootingSolver::solve).
  static Eigen::VectorXd actuation_vector(const Actuation& act) {
    int n = 9;
    for (const ActuatorDrive& d : act.actuators) n += 1 + 2 * static_cast<int>(d.segments.size());
    Eigen::VectorXd a(n);
    int k = 0;
    for (const ActuatorDrive& d : act.actuators) {
      a[k++] = d.tension_N;
      for (const tca::Segment& seg : d.segments) {
        a[k++] = seg.fraction;
        a[k++] = seg.temperature_K;
      }
    }
    a.segment<3>(k) = act.tip_force_W_N;
    a.segment<3>(k + 3) = act.tip_moment_W_Nm;
    a.segment<3>(k + 6) = act.gravity_W_m_s2;
    return a;
  }

  /// Extrapolates the unknowns to the actuation a along Solution::path: the newest points
  /// whose actuations lie on the line through the last one and a, with parameter t (0 at
  /// the last point, 1 at a), each older point at least kPathMinSpacing behind the next (no
  /// wild extrapolation from clustered points), are interpolated by the Lagrange polynomial
  /// in t evaluated at t = 1. Returns false when fewer than two points qualify (or a is the
  /// last point's actuation).
  static bool extrapolate_path(const Solution& sol, const Eigen::VectorXd& a, int nx,
                               Eigen::VectorXd& x) {
    const auto& path = sol.path;
    if (path.size() < 2) return false;
    const Solution::PathPoint& last = path.back();
    if (last.actuation.size() != a.size() || last.unknowns.size() != nx) return false;
    const Eigen::VectorXd d = a - last.actuation;
    const double dd = d.squaredNorm();
    if (!(dd > 0.0) || !std::isfinite(dd)) return false;
    std::vector<double> t{0.0};
    for (int k = static_cast<int>(path.size()) - 2; k >= 0; --k) {
      const Solution::PathPoint& p = path[k];
      if (p.actuation.size() != a.size() || p.unknowns.size() != nx) break;
      const Eigen::VectorXd v = p.actuation - last.actuation;
      const double tk = v.dot(d) / dd;
      // On the line (to round-off of the actuation values) and behind the previous node.
      if ((v - tk * d).norm() > kPathCollinearity * (v.norm() + std::sqrt(dd))) break;
      if (tk > t.back() - kPathMinSpacing) break;
      t.push_back(tk);
    }
    const int m = static_cast<int>(t.size());
    if (m < 2) return false;
    x.setZero(nx);
    for (int k = 0; k < m; ++k) {
      double w = 1.0;  // Lagrange basis polynomial of node t[k] at t = 1
      for (int l = 0; l < m; ++l) {
        if (l != k) w *= (1.0 - t[l]) / (t[k] - t[l]);
      }
      x += w * path[path.size() - 1 - k].unknowns;  // t[k] belongs to the k-th newest point
    }
    return x.allFinite();
  }

  /// Updates Solution::path after a solve (see its documentation).
  static void record_path(Solution& sol, bool warm, bool converged, Eigen::VectorXd a) {
    if (!converged) {
      sol.path.clear();
      return;
    }
    if (!warm) sol.path.clear();
    if (!sol.path.empty() && sol.path.back().actuation.size() == a.size() &&
        sol.path.back().actuation == a) {
      sol.path.back().unknowns = sol.unknowns;  // the same point again: no duplicate node
      return;
    }
    sol.path.push_back({std::move(a), sol.unknowns});
    if (static_cast<int>(sol.path.size()) > ShootingSolver::kPathHistory) sol.path.erase(sol.path.begin());
  }

  void remember(double lambda, const Eigen::VectorXd& x) {
    acc_full_load = lambda == 1.0 && active_plain == &integrator;
    memo_valid = y.allFinite();
    acc_cT = cT;
    acc_f_ext = f_ext_W;
    acc_dphi_dT = dphi_dT;
    acc_dphi_ddelta = dphi_ddelta;
    acc_level = active_plain;
    y_acc = y;
    x_acc = x;
  }

  /// Planar reduction: the in-plane unknowns (nu_x, nu_z - 1, omega_y, T_tca...) of 3-D unknowns.
  Eigen::VectorXd reduce(const Eigen::VectorXd& x3) const {
    Eigen::VectorXd x(nx);
    x << x3[0], x3[2], x3[4], x3.segment(6, n_tca);
    return x;
  }

  /// Whether 3-D unknowns lie in the plane of the planar reduction (exact zeros).
  static bool in_plane(const Eigen::VectorXd& x3) {
    return x3[1] == 0.0 && x3[3] == 0.0 && x3[5] == 0.0;
  }

  /// Planar reduction: the 3-D unknowns of reduced ones.
  Eigen::VectorXd embed_unknowns(const Eigen::VectorXd& x) const {
    Eigen::VectorXd x3(6 + n_tca);
    x3 << x[0], 0.0, x[1], 0.0, x[2], 0.0, x.tail(n_tca);
    return x3;
  }

  /// Planar reduction: the 3-D IVP state (layout of shooting.hpp) of a planar one.
  Eigen::VectorXd embed_state(const Eigen::VectorXd& yp) const {
    const Mat3& R0 = model.R_WB0;
    const Vec3 p0 = model.base_position_W_m;
    Eigen::VectorXd y3 = Eigen::VectorXd::Zero(state_dimension(model));
    y3.segment<3>(state_layout::kP) = p0 + R0 * Vec3(yp[planar::kQ], 0.0, yp[planar::kQ + 1]);
    const double c = yp[planar::kCS], s = yp[planar::kCS + 1];
    Mat3 rot;
    rot << c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c;
    Eigen::Map<Mat3>(y3.data() + state_layout::kR) = R0 * rot;
    y3.segment<3>(state_layout::kNu) = Vec3(yp[planar::kNu], 0.0, yp[planar::kNu + 1]);
    y3.segment<3>(state_layout::kOmega) = Vec3(0.0, yp[planar::kKappa], 0.0);
    y3.segment<3>(state_layout::kC) = L * p0 + R0 * Vec3(yp[planar::kC], 0.0, yp[planar::kC + 1]);
    y3.tail(n_act) = yp.tail(n_act);
    return y3;
  }

  /// Summary::equilibrium_residual of the scaled residual r at full load.
  double equilibrium_residual(const Actuation& act, const Eigen::VectorXd& r) const {
    const double k_c = K_nu.maxCoeff();  // constraint rows hold c . (p - p_target) / L
    double force = 0.0;
    for (int i = 0; i < r.size(); ++i) {
      const bool constraint = n_con > 0 && i >= k_con && i < k_con + n_con;
      force = std::max(force, std::abs(r[i]) * (constraint ? k_c : Fc));
    }
    return force / rod::characteristic_force_N(model, act);
  }

  void finish(const Actuation& act, const Eigen::VectorXd& x, Solution& sol, Summary& summary) {
    Eigen::VectorXd r;
    summary.characteristic_force_N = rod::characteristic_force_N(model, act);
    summary.equilibrium_residual.reset();
    sol.unknowns = x;
    sol.tensions_N.assign(n_act, 0.0);
    sol.elongations_m.assign(n_act, 0.0);
    if (acc_full_load && x_acc.size() == x.size() && x_acc == x) {
      set_parameters(act, 1.0, x);  // no IVP: y(L) of this point is known
      y = y_acc;
      if (!tip_residual(act, 1.0, x, y, r)) r.resize(0);
    } else if (!residual(act, 1.0, x, r)) {
      // Only the last accepted point of a failed continuation can land here; keep finite zeros.
      sol.tip_state.resize(0);
      return;
    }
    sol.tip_state = y;
    if (r.size() == nx) summary.equilibrium_residual = equilibrium_residual(act, r);
    for (int i = 0; i < n_act; ++i) {
      sol.tensions_N[i] = cT[i] / count[i];
      sol.elongations_m[i] = y[(planar ? planar::kDelta : kDelta) + i];
    }
    if (!planar) equilibrium(act, x, y, summary);  // planar: by the 3-D Impl after embedding
  }

  /// Global equilibrium (docs/conventions.md): n(0), m(0) of the 3-D unknowns x against the
  /// applied loads, with yL = y(L) (3-D layout) and cT, f_ext_W set for x at full load.
  void equilibrium(const Actuation& act, const Eigen::VectorXd& x, const Eigen::VectorXd& yL,
                   Summary& summary) const {
    const Mat3& R0 = model.R_WB0;
    const Vec3 p0 = model.base_position_W_m;
    const Vec3 n0 = R0 * K_nu.cwiseProduct(x.head<3>());  // x holds nu(0) - nu*
    const Vec3 m0 = R0 * K_omega.cwiseProduct(x.segment<3>(3) - omega_star);
    const Vec3 w = f_ext_W;
    const Vec3 pL = yL.segment<3>(kP);
    const Vec3 c = yL.segment<3>(kC);
    const Vec3 F_tip = act.tip_force_W_N + reaction_W(x);  // applied load plus the holder's
    Vec3 n_exp = F_tip + L * w;
    Vec3 m_exp = act.tip_moment_W_Nm + (pL - p0).cross(F_tip) + (c - L * p0).cross(w);
    for (int i = 0; i < n_act; ++i) {
      const rod::Routing& ro = model.actuators[i].routing;
      const Vec3 r0 = ro.r(0.0);
      const Vec3 t0 =
          R0 * (nu_star + x.head<3>() + x.segment<3>(3).cross(r0) + ro.dr(0.0)).normalized();
      n_exp -= cT[i] * t0;
      m_exp -= (R0 * r0).cross(cT[i] * t0);
    }
    summary.force_imbalance_W_N = n0 - n_exp;
    summary.moment_imbalance_W_Nm = m0 - m_exp;
    if (!summary.force_imbalance_W_N.allFinite()) summary.force_imbalance_W_N.setZero();
    if (!summary.moment_imbalance_W_Nm.allFinite()) summary.moment_imbalance_W_Nm.setZero();
  }

  /// Direct solve at full load from x (warm: the previous solution, J its Jacobian; cold: the
  /// guess, J empty) with the two-level start (Options::coarse_steps); on return x and J are
  /// the last accepted point and its Jacobian, and sol's coarse fields are set.
  Summary::Status direct_solve(const Actuation& act, Solution& sol, bool warm, Eigen::VectorXd& x,
                               Eigen::MatrixXd& J, Summary& summary, std::string& why) {
    // Two-level start (Options::coarse_steps). Cold: converge the coarse problem first
    // (cheap IVPs); its solution is within the coarse discretization error of the fine one.
    // Warm: coarse-grid correction x = x_fine,old + (x_coarse,new - x_coarse,old), whose
    // error is the change of the discretization error between the two actuations.
    Eigen::VectorXd coarse_x;
    Eigen::MatrixXd coarse_J;
    if (coarse_integrator) {
      const bool warm_coarse = warm && sol.coarse_unknowns.size() == nx &&
                               sol.coarse_unknowns.allFinite();
      // A warm start with a Jacobian goes straight to the fine level: its first residual is
      // usually free (IVP memo), and the Broyden-updated Jacobian saves the coarse solve.
      const bool warm_fine = warm && J.rows() == nx && options.warm_start_fine_only;
      if ((!warm || warm_coarse) && !warm_fine) {
        Eigen::VectorXd xc = warm ? sol.coarse_unknowns : x;
        Eigen::MatrixXd Jc = warm && sol.coarse_jacobian.rows() == nx ? sol.coarse_jacobian
                                                                       : Eigen::MatrixXd();
        std::string coarse_why;
        use_level(true);
        const Summary::Status sc =
            newton(act, 1.0, xc, Jc, summary, coarse_why, kCoarseTolerance);
        use_level(false);
        if (sc == Summary::Status::kConverged) {
          if (warm) {
            x += xc - sol.coarse_unknowns;
          } else {
            x = xc;
            // A Jacobian updated more than once since it was computed has drifted far from
            // the one at xc: the fine level then starts with a fresh (coarse-level) one.
            if (jacobian_updates <= kMaxHandedOverUpdates) J = Jc;
            if (mid_integrator) cold_extrapolation(act, xc, Jc, x, J, summary);
          }
          coarse_x = xc;
          coarse_J = Jc;
        }
      }
    }
    sol.coarse_unknowns = coarse_x;
    sol.coarse_jacobian = coarse_J;
    if (warm && J.rows() == nx && coarse_x.size() == 0) refresh_tca_rows(act, x, J);
    return newton(act, 1.0, x, J, summary, why, options.tolerance);
  }

  Summary solve(const Actuation& act, Solution& sol) {
    const auto t0 = std::chrono::steady_clock::now();
    Summary summary;
    ivp_count = 0;
    acc_full_load = false;
    coarse_jacobian_x.resize(0);  // a solve never depends on where an earlier one took Jacobians
    // Messages are built only on failure (solve is called in sweeps and design loops).
    if (static_cast<int>(act.actuators.size()) != n_act) {
      throw_input_error("actuation.actuators", static_cast<double>(act.actuators.size()),
                        "must have one entry per model actuator (" + std::to_string(n_act) + ")");
    }
    for (int i = 0; i < n_act; ++i) {
      if (unknown_of[i] >= 0 && act.actuators[i].segments.empty()) {
        throw_input_error("actuation.actuators[" + std::to_string(i) + "].segments", 0.0,
                          "must not be empty for a TCA drive");
      }
    }
    const bool warm = sol.valid && sol.unknowns.size() == nx && sol.unknowns.allFinite();
    auto done = [&](Summary::Status st, std::string why, const Eigen::VectorXd& x) {
      summary.status = st;
      summary.message = st == Summary::Status::kConverged ? std::string() : std::move(why);
      finish(act, x, sol, summary);
      sol.valid = st == Summary::Status::kConverged;
      record_path(sol, warm, sol.valid, actuation_vector(act));
      summary.ivp_count = ivp_count;
      summary.wall_time_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return summary;
    };

    std::string why;
    if (warm) {
      // A sweep: start from the extrapolation along the path, with a fresh (coarse-level)
      // sensitivity Jacobian there if there is a coarse level, else the last one; fall back
      // to the last solution if that start does not converge.
      Eigen::VectorXd xp;
      Eigen::MatrixXd Jp;
      if (!coarse_sens_integrator) Jp = sol.jacobian;
      if (extrapolate_path(sol, actuation_vector(act), nx, xp) &&
          newton(act, 1.0, xp, Jp, summary, why, options.tolerance) == Summary::Status::kConverged) {
        sol.jacobian = Jp;
        sol.coarse_unknowns.resize(0);
        sol.coarse_jacobian.resize(0, 0);
        return done(Summary::Status::kConverged, "", xp);
      }
    }
    bool loaded_guess = false;
    Eigen::VectorXd x = warm ? sol.unknowns : initial_guess(act, 1.0, true, &loaded_guess);
    Eigen::MatrixXd J = (warm && sol.jacobian.rows() == nx) ? sol.jacobian : Eigen::MatrixXd();
    Summary::Status st = direct_solve(act, sol, warm, x, J, summary, why);
    if (st != Summary::Status::kConverged && loaded_guess) {
      // Strong gravity can bend the guess toward another equilibrium or out of Newton's
      // reach: retry from the guess without it before continuation.
      x = initial_guess(act, 1.0, false);
      J.resize(0, 0);
      std::string retry_why;
      st = direct_solve(act, sol, false, x, J, summary, retry_why);
      why = "from the guess with gravity: " + why + "; without: " + retry_why;
    }
    if (st == Summary::Status::kConverged || !options.continuation) {
      sol.jacobian = J;
      return done(st, why, x);
    }

    // Continuation in the load fraction lambda, warm-starting each step (fine level only).
    sol.coarse_unknowns.resize(0);
    sol.coarse_jacobian.resize(0, 0);
    const std::string direct_why = why;
    double lambda = 0.0;
    Eigen::VectorXd xc = initial_guess(act, 0.0, false);
    Eigen::MatrixXd Jc;
    st = newton(act, 0.0, xc, Jc, summary, why, options.tolerance);
    if (st != Summary::Status::kConverged) {
      sol.jacobian.resize(0, 0);
      return done(st, "direct solve: " + direct_why + "; unloaded solve: " + why, xc);
    }
    double step = 0.5;
    while (lambda < 1.0) {
      const double lt = std::min(1.0, lambda + step);
      Eigen::VectorXd xt = xc;
      Eigen::MatrixXd Jt = Jc;
      st = newton(act, lt, xt, Jt, summary, why, options.tolerance);
      if (st == Summary::Status::kConverged) {
        lambda = lt;
        xc = xt;
        Jc = Jt;
        ++summary.continuation_steps;
        step = std::min(2.0 * step, 1.0 - lambda);  // never retry a failed target
      } else {
        step *= 0.5;
        if (step < options.min_continuation_step) {
          sol.jacobian.resize(0, 0);
          // Report the residual at the full load for the returned point.
          Eigen::VectorXd r;
          summary.residual = residual(act, 1.0, xc, r) ? r.lpNorm<Eigen::Infinity>()
                                                       : std::numeric_limits<double>::infinity();
          return done(Summary::Status::kContinuationFailed,
                      "continuation stalled at load fraction " + format_value(lambda) +
                          " (step < " + format_value(options.min_continuation_step) +
                          "): " + why,
                      xc);
        }
      }
    }
    sol.jacobian = Jc;
    return done(Summary::Status::kConverged, "", xc);
  }

  /// Solves a planar problem (planar_model and planar_loads hold) with the planar Impl `p`:
  /// the unknowns and tip state of `sol` are 3-D on entry and on return (the Jacobians, the
  /// coarse-level fields and the path stay in p's reduced unknowns); the global equilibrium
  /// is checked on the embedded 3-D solution.
  Summary solve_planar(Impl& p, const Actuation& act, Solution& sol) {
    if (sol.valid && sol.unknowns.size() == nx && sol.unknowns.allFinite()) {
      sol.unknowns = p.reduce(sol.unknowns);
    }
    Summary summary = p.solve(act, sol);
    summary.planar = true;
    if (sol.unknowns.size() == p.nx) sol.unknowns = p.embed_unknowns(sol.unknowns);
    if (sol.tip_state.size() == p.dim) {
      sol.tip_state = p.embed_state(sol.tip_state);
      set_parameters(act, 1.0, sol.unknowns);
      equilibrium(act, sol.unknowns, sol.tip_state, summary);
    }
    return summary;
  }

  rod::Result make_result(const Actuation& act, const Solution& sol, const Summary& summary) {
    rod::Result res;
    res.scenario = model.name;
    res.method = "cosserat";
    if (ode::is_fixed_step(options.integrator.method)) {
      res.discretization = {{"steps", static_cast<double>(options.integrator.steps)}};
      // RK4 (the paper's scheme) is the default and has no key; other schemes name their order.
      if (options.integrator.method != ode::Method::kRk4) {
        res.discretization.push_back({"order", static_cast<double>(ode::order_of(options.integrator.method))});
      }
    } else {
      res.discretization = {{"rtol", options.integrator.relative_tolerance}};
    }
    res.converged = summary.converged();
    res.iterations = summary.iterations;
    res.residual = std::isfinite(summary.residual) ? summary.residual : 0.0;
    res.wall_time_s = summary.wall_time_s;
    res.message = summary.message;
    res.actuators.resize(n_act);
    for (int i = 0; i < n_act; ++i) res.actuators[i].name = model.actuators[i].name;

    if (sol.unknowns.size() != nx || !sol.unknowns.allFinite()) {
      res.converged = false;
      if (res.message.empty()) res.message = "no solution to report";
      return res;
    }
    if (!output_integrator) {
      ode::IntegratorOptions io = options.integrator;
      io.output_intervals = options.centerline_intervals;
      if (io.method == ode::Method::kCvode && io.output_intervals == 0) io.output_intervals = 64;
      output_integrator.emplace(dim, io);
    }
    set_parameters(act, 1.0, sol.unknowns);
    initial_state(sol.unknowns, y);
    auto observer = [&res](double s, const Eigen::VectorXd& yy) {
      res.centerline_s_m.push_back(s);
      res.centerline_p_W_m.push_back(yy.segment<3>(kP));
      res.centerline_R_WB.push_back(Eigen::Map<const Mat3>(yy.data() + kR));
    };
    bool sampled = false;
    if (lie_plain) {
      // Every step node, or every (steps / centerline_intervals)-th (validated to divide).
      const int every = options.centerline_intervals > 0
                            ? options.integrator.steps / options.centerline_intervals : 1;
      int node = 0;
      auto every_observer = [&](double s, const Eigen::VectorXd& yy) {
        if (node++ % every == 0) observer(s, yy);
      };
      sampled = lie_plain->integrate(rhs, 0.0, L, y, every_observer) && y.allFinite();
    } else {
      const ode::IntegrationSummary is = output_integrator->integrate(rhs, 0.0, L, y, observer);
      sampled = is.status == ode::IntegrationSummary::Status::kSuccess && y.allFinite();
    }
    if (!sampled) {
      res.converged = false;
      res.message = "IVP failed while sampling the solution";
      res.centerline_s_m.clear();
      res.centerline_p_W_m.clear();
      res.centerline_R_WB.clear();
      return res;
    }
    res.tip_position_W_m = y.segment<3>(kP);
    res.tip_R_WB = Eigen::Map<const Mat3>(y.data() + kR);
    if (n_con > 0) res.tip_reaction_force_W_N = reaction_W(sol.unknowns);
    for (int i = 0; i < n_act; ++i) {
      res.actuators[i].tension_N = cT[i] / count[i];
      res.actuators[i].elongation_m = y[kDelta + i];
      rod::set_coil_contacts(model.actuators[i], act.actuators[i].segments, res.actuators[i]);
    }
    try {
      res.bending_radius_m = rod::three_point_inner_radius(model, res.centerline_s_m,
                                                           res.centerline_p_W_m, res.centerline_R_WB);
    } catch (const DomainError&) {
      res.bending_radius_m.reset();
    }
    return res;
  }
};

// ---------------------------------------------------------------------------------------
ShootingSolver::ShootingSolver(const rod::RodModel& model, const Options& options)
    : impl_(std::make_unique<Impl>(model, options)) {
  if (Impl::planar_model(model, impl_->options)) {
    planar_ = std::make_unique<Impl>(model, options, impl_.get());
  }
}
ShootingSolver::~ShootingSolver() = default;
ShootingSolver::ShootingSolver(ShootingSolver&&) noexcept = default;

Summary ShootingSolver::solve(const Actuation& actuation, Solution& solution) {
  if (actuation.load_scale != 1.0) return solve(actuation.applied(impl_->model), solution);
  // The planar reduction needs a planar actuation and, for a warm start, in-plane unknowns
  // (a 3-D equilibrium that left the plane stays a 3-D problem).
  const bool out_of_plane_start = solution.valid && solution.unknowns.size() == impl_->nx &&
                                  !Impl::in_plane(solution.unknowns);
  if (planar_ && impl_->planar_loads(actuation) && !out_of_plane_start) {
    return impl_->solve_planar(*planar_, actuation, solution);
  }
  return impl_->solve(actuation, solution);
}

rod::Result ShootingSolver::make_result(const Actuation& actuation, const Solution& solution,
                                        const Summary& summary) {
  rod::Result res = actuation.load_scale != 1.0
                        ? impl_->make_result(actuation.applied(impl_->model), solution, summary)
                        : impl_->make_result(actuation, solution, summary);
  res.status = to_string(summary.status);
  res.residual = summary.equilibrium_residual;
  res.characteristic_force_N = summary.characteristic_force_N;
  return res;
}

Eigen::VectorXd ShootingSolver::initial_guess(const Actuation& actuation) {
  return impl_->initial_guess(actuation, 1.0, true);
}

bool ShootingSolver::residual(const Actuation& actuation, const Eigen::VectorXd& x,
                              Eigen::VectorXd& r) {
  return impl_->residual(actuation, 1.0, x, r);
}

bool ShootingSolver::jacobian(const Actuation& actuation, const Eigen::VectorXd& x,
                              Eigen::MatrixXd& J) {
  Eigen::VectorXd r0;
  if (impl_->options.jacobian == JacobianMethod::kSensitivity) {
    return impl_->residual_and_jacobian(actuation, 1.0, x, r0, J);
  }
  if (!impl_->residual(actuation, 1.0, x, r0)) return false;
  return impl_->fd_jacobian(actuation, 1.0, x, r0, J);
}

bool ShootingSolver::residual_and_tip_state(const Actuation& actuation, const Eigen::VectorXd& x,
                                            Eigen::VectorXd& r, Eigen::VectorXd& tip_state) {
  if (!impl_->residual(actuation, 1.0, x, r)) return false;
  tip_state = impl_->y;
  return true;
}

bool ShootingSolver::tip_sensitivities(const Actuation& actuation, const Eigen::VectorXd& x,
                                       Eigen::VectorXd& r, Eigen::MatrixXd& J,
                                       Eigen::VectorXd& tip_state, Eigen::MatrixXd& dtip_dx) {
  if (impl_->options.jacobian != JacobianMethod::kSensitivity) return false;
  if (!impl_->residual_and_jacobian(actuation, 1.0, x, r, J)) return false;
  const int dim = impl_->dim, nx = impl_->nx;
  tip_state = impl_->y;
  dtip_dx.resize(dim, nx);
  for (int j = 0; j < nx; ++j) dtip_dx.col(j) = impl_->Y.segment(dim * (j + 1), dim);
  return true;
}

int ShootingSolver::state_dimension() const { return impl_->dim; }
int ShootingSolver::unknown_count() const { return impl_->nx; }
double ShootingSolver::characteristic_force_N() const { return impl_->Fc; }
const Options& ShootingSolver::options() const { return impl_->options; }

rod::Result solve(const rod::RodModel& model, const Options& options) {
  ShootingSolver solver(model, options);
  const Actuation act = Actuation::from_model(model);
  Solution sol;
  const Summary summary = solver.solve(act, sol);
  return solver.make_result(act, sol, summary);
}

}  // namespace tcasim::cosserat
