// The planar reduction as a layout of the shooting problem (cosserat/internal/layout.hpp): when it
// applies, the planar right-hand sides and tip wrench of cosserat/internal/planar.hpp bound to the
// problem's parameters, and its unknowns and IVP states mapped to and from the 3-D layout of
// cosserat/shooting.hpp (docs/conventions.md "Planar reduction").
#include "cosserat/internal/planar.hpp"
#include "cosserat/internal/tip_conditions.hpp"
#include "rod/loads.hpp"

namespace tcasim::cosserat::internal {
namespace {

class PlanarLayout final : public Layout {
 public:
  explicit PlanarLayout(const rod::RodModel& m)
      : model_(m), n_act_(static_cast<int>(m.actuators.size())) {
    for (const rod::Actuator& a : m.actuators) n_tca_ += a.drive.type == rod::Drive::Type::kTca;
  }

  LayoutDims dims() const override { return {3, planar::kNu, planar::kDelta}; }
  bool reduced() const override { return true; }

  /// Loads that keep the model in its plane (gravity and tip force without a component
  /// along R_WB0 e_y, the tip moment along it only; exact tests) and, for a warm start,
  /// in-plane unknowns (a 3-D equilibrium that left the plane stays a 3-D problem).
  bool admits(const rod::Loads& act, const Solution& start) const override {
    const Mat3& R0 = model_.R_WB0;
    const bool planar_loads =
        R0.col(1).dot(act.gravity_W_m_s2) == 0.0 && R0.col(1).dot(act.tip_force_W_N) == 0.0 &&
        R0.col(0).dot(act.tip_moment_W_Nm) == 0.0 && R0.col(2).dot(act.tip_moment_W_Nm) == 0.0;
    const Eigen::VectorXd& x3 = start.unknowns;
    const bool out_of_plane_start =
        start.valid && x3.size() == 6 + n_tca_ && (x3[1] != 0.0 || x3[3] != 0.0 || x3[5] != 0.0);
    return planar_loads && !out_of_plane_start;
  }

  void bind(RodRhs& p, bool sensitivities) override {
    rod_.kn_x = p.K_nu.x();
    rod_.kn_z = p.K_nu.z();
    rod_.kw_y = p.K_omega.y();
    for (int i = 0; i < p.n_act; ++i) {
      rod_.rho.push_back(p.model.actuators[i].routing.offset_m.x());
      rod_.length_ratio.push_back(p.length_ratio[i]);
      rod_.count.push_back(p.count[i]);
      rod_.direction_of.push_back(p.unknown_of[i]);
    }
    rod_.cT.assign(p.n_act, 0.0);
    const planar::Rod* rod = &rod_;
    p.rhs = [rod](double, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
      planar::rhs(*rod, yy.data(), dy.data());
    };
    if (sensitivities) {
      const int dim = p.dim, nx = p.nx;
      p.rhs_sens = [rod, dim, nx](double, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
        planar::rhs_sens(*rod, dim, nx, yy.data(), dy.data());
      };
    }
  }

  void set_parameters(const RodRhs& p) override {
    rod_.cT = p.cT;
    const Vec3 f_B0 = p.model.R_WB0.transpose() * p.f_ext_W;
    rod_.f_x = f_B0.x();
    rod_.f_z = f_B0.z();
  }

  void initial_state(const RodRhs&, const Eigen::VectorXd& x, Eigen::VectorXd& y0) const override {
    y0.setZero();
    y0[planar::kCS] = 1.0;                     // Rot_y(0) = I
    y0.segment<3>(planar::kNu) = x.head<3>();  // (nu_x, nu_z - 1, kappa) are contiguous
  }

  /// The in-plane rows (force x, z; moment y) of the 3-D residual; the others are zero.
  void tip_rows(const TipConditions& p, const rod::Loads& act, double lambda,
                const Eigen::VectorXd&, const Eigen::VectorXd& yL,
                Eigen::VectorXd& r) const override {
    const Vec3 F_B0 =
        model_.R_WB0.transpose() * (lambda * rod::tip_force_with_weight_W_N(model_, act));
    const double M_y = model_.R_WB0.col(1).dot(lambda * act.tip_moment_W_Nm);
    double w[3];
    planar::tip_wrench(rod_, p.omega_star.y(), F_B0.x(), F_B0.z(), M_y, yL.data(), w);
    r[0] = w[0] / p.Fc;
    r[1] = w[1] / p.Fc;
    r[2] = w[2] / (p.Fc * p.L);
  }

  /// The tip wrench rows by planar::tip_wrench_sens.
  void tip_rows_jacobian(const TipConditions& p, const rod::Loads& act, double lambda,
                         const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd& Y,
                         Eigen::MatrixXd& J) const override {
    const Vec3 F_B0 =
        model_.R_WB0.transpose() * (lambda * rod::tip_force_with_weight_W_N(model_, act));
    double dw[3 * planar::kMaxDirections];
    planar::tip_wrench_sens(rod_, F_B0.x(), F_B0.z(), p.dim, p.nx, Y.data(), dw);
    for (int j = 0; j < p.nx; ++j) {
      J(0, j) = dw[3 * j] / p.Fc;
      J(1, j) = dw[3 * j + 1] / p.Fc;
      J(2, j) = dw[3 * j + 2] / (p.Fc * p.L);
    }
  }

  /// The in-plane unknowns (nu_x, nu_z - 1, omega_y, T_tca...) of 3-D unknowns.
  void reduce_unknowns(Eigen::VectorXd& x3) const override {
    if (x3.size() != 6 + n_tca_) return;
    Eigen::VectorXd x(3 + n_tca_);
    x << x3[0], x3[2], x3[4], x3.segment(6, n_tca_);
    x3 = std::move(x);
  }

  void embed_unknowns(Eigen::VectorXd& x) const override {
    Eigen::VectorXd x3(6 + n_tca_);
    x3 << x[0], 0.0, x[1], 0.0, x[2], 0.0, x.tail(n_tca_);
    x = std::move(x3);
  }

  void embed_state(const Eigen::VectorXd& yp, Eigen::VectorXd& y3) const override {
    const Mat3& R0 = model_.R_WB0;
    const Vec3 p0 = model_.base_position_W_m;
    const double L = model_.length_m;
    y3.resize(state_layout::kDelta + n_act_);  // every entry is set below
    y3.segment<3>(state_layout::kP) = p0 + R0 * Vec3(yp[planar::kQ], 0.0, yp[planar::kQ + 1]);
    const double c = yp[planar::kCS], s = yp[planar::kCS + 1];
    Mat3 rot;
    rot << c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c;
    Eigen::Map<Mat3>(y3.data() + state_layout::kR) = R0 * rot;
    y3.segment<3>(state_layout::kNu) = Vec3(yp[planar::kNu], 0.0, yp[planar::kNu + 1]);
    y3.segment<3>(state_layout::kOmega) = Vec3(0.0, yp[planar::kKappa], 0.0);
    y3.segment<3>(state_layout::kC) = L * p0 + R0 * Vec3(yp[planar::kC], 0.0, yp[planar::kC + 1]);
    y3.tail(n_act_) = yp.tail(n_act_);
  }

 private:
  const rod::RodModel& model_;
  int n_act_ = 0;
  int n_tca_ = 0;
  planar::Rod rod_;  // the planar rod and the parameters of the current IVP
};

}  // namespace

std::unique_ptr<Layout> make_planar_layout(const rod::RodModel& m, const Options& o) {
  if (!o.planar_reduction || !ode::is_fixed_step(o.integrator.method) ||
      o.kinematics != Kinematics::kFlat || o.jacobian != JacobianMethod::kSensitivity ||
      m.tip_constraint || static_cast<int>(m.actuators.size()) > planar::kMaxActuators) {
    return nullptr;
  }
  // The planar right-hand sides have constant properties: a body that varies along s is
  // solved in 3-D (its pieces and jumps are RodRhs's).
  if (!m.uniform_body() || m.has_inner_anchors()) return nullptr;
  const Eigen::Vector3d omega_star = m.reference_curvature_at(0.0);
  if (omega_star.x() != 0.0 || omega_star.z() != 0.0) {
    return nullptr;
  }
  int n_tca = 0;
  for (const rod::Actuator& a : m.actuators) {
    if (a.routing.type != rod::Routing::Type::kStraight || a.routing.offset_m.y() != 0.0) {
      return nullptr;
    }
    if (a.drive.type == rod::Drive::Type::kTca) ++n_tca;
  }
  if (3 + n_tca > planar::kMaxDirections) return nullptr;
  return std::make_unique<PlanarLayout>(m);
}

}  // namespace tcasim::cosserat::internal
