// The 3-D layout of the shooting problem (cosserat/internal/layout.hpp): the state and unknowns of
// cosserat/shooting.hpp, the right-hand sides of RodRhs (rhs.cpp), and the tip wrench and
// tip-constraint rows of the residual (docs/conventions.md "Tip conditions").
#include "cosserat/internal/layout.hpp"
#include "cosserat/internal/tip_conditions.hpp"
#include "rod/loads.hpp"

namespace tcasim::cosserat::internal {
namespace {

using namespace state_layout;

class Layout3d final : public Layout {
 public:
  LayoutDims dims() const override { return {6, kNu, kDelta}; }
  bool reduced() const override { return false; }
  bool admits(const rod::Loads&, const Solution&) const override { return true; }

  void bind(RodRhs& p, bool sensitivities) override {
    RodRhs* q = &p;
    p.rhs = [q](double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
      q->eval_rhs(s, yy, dy);
    };
    if (sensitivities) {
      p.rhs_sens = [q](double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) {
        q->eval_rhs_sens(s, yy, dy);
      };
    }
  }

  void set_parameters(const RodRhs&) override {}

  void initial_state(const RodRhs& p, const Eigen::VectorXd& x,
                     Eigen::VectorXd& y0) const override {
    y0.setZero();
    y0.segment<3>(kP) = p.model.base_position_W_m;
    Eigen::Map<Mat3>(y0.data() + kR) = p.model.R_WB0;
    y0.segment<3>(kNu) = x.head<3>();
    y0.segment<3>(kOmega) = x.segment<3>(3);
  }

  // docs/conventions.md "Tip conditions" (body frame), scaled.
  void tip_rows(const TipConditions& p, const rod::Loads& act, double lambda,
                const Eigen::VectorXd& x, const Eigen::VectorXd& yL,
                Eigen::VectorXd& r) const override {
    const rod::RodModel& model = p.model;
    const Eigen::Map<const Mat3> R(yL.data() + kR);
    const Vec3 e = yL.segment<3>(kNu);  // nu - nu*
    const Vec3 nu = p.nu_star + e;
    const Vec3 omega = yL.segment<3>(kOmega);
    // The holder's reaction (an unknown, not scaled by lambda) adds to the applied tip force.
    Vec3 rn =
        p.K_nu_tip.cwiseProduct(e) -
        R.transpose() * (lambda * rod::tip_force_with_weight_W_N(model, act) + p.reaction_W(x));
    Vec3 rm = p.K_omega_tip.cwiseProduct(omega - p.omega_star_tip) -
              R.transpose() * (lambda * act.tip_moment_W_Nm);
    for (int i = 0; i < p.n_act; ++i) {
      if (p.cT[i] == 0.0 || !p.to_tip(i)) continue;  // a string anchored before L: not at the tip
      const Vec3 ri = model.actuators[i].routing.r(p.L);
      const Vec3 q = nu + omega.cross(ri) + model.actuators[i].routing.dr(p.L);
      const Vec3 qh = q.normalized();
      rn += p.cT[i] * qh;
      rm += p.cT[i] * ri.cross(qh);
    }
    r.head<3>() = rn / p.Fc;
    r.segment<3>(3) = rm / (p.Fc * p.L);
    // Tip constraint: position error (pinned) or its normal component, scaled by L.
    if (p.n_con == 3) r.segment<3>(p.k_con) = (yL.segment<3>(kP) - p.con_target_W) / p.L;
    if (p.n_con == 1) r[p.k_con] = p.con_normal_W.dot(yL.segment<3>(kP) - p.con_target_W) / p.L;
  }

  void tip_rows_jacobian(const TipConditions& p, const rod::Loads& act, double lambda,
                         const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& Y, Eigen::MatrixXd& J) const override {
    // Chain rule through the tip conditions: dr = (dr/dy) Y(L) + dr/dT.
    const rod::RodModel& model = p.model;
    const Eigen::Map<const Mat3> R(y.data() + kR);
    const Vec3 nu = p.nu_star + y.segment<3>(kNu), omega = y.segment<3>(kOmega);
    const Vec3 F_e = lambda * rod::tip_force_with_weight_W_N(model, act) + p.reaction_W(x),
               M_e = lambda * act.tip_moment_W_Nm;
    for (int j = 0; j < p.nx; ++j) {
      const double* yj = Y.data() + p.dim * (j + 1);
      const Eigen::Map<const Mat3> dR(yj + kR);
      const Vec3 dnu(yj + kNu), dom(yj + kOmega);
      Vec3 drn = p.K_nu_tip.cwiseProduct(dnu) - dR.transpose() * F_e;
      Vec3 drm = p.K_omega_tip.cwiseProduct(dom) - dR.transpose() * M_e;
      for (int i = 0; i < p.n_act; ++i) {
        const double dcT = p.unknown_of[i] == j ? p.count[i] : 0.0;
        if ((p.cT[i] == 0.0 && dcT == 0.0) || !p.to_tip(i)) continue;
        const rod::Routing& ro = model.actuators[i].routing;
        const Vec3 ri = ro.r(p.L);
        const Vec3 q = nu + omega.cross(ri) + ro.dr(p.L);
        const double qn = q.norm();
        const Vec3 qh = q / qn;
        const Vec3 dq = dnu + dom.cross(ri);
        const Vec3 dqh = (dq - qh * qh.dot(dq)) / qn;
        const Vec3 dF = dcT * qh + p.cT[i] * dqh;
        drn += dF;
        drm += ri.cross(dF);
      }
      // A reaction unknown enters only the tip force (its IVP sensitivity is zero).
      if (j >= p.k_con) {
        drn -= R.transpose() * (p.n_con == 3 ? Vec3::Unit(j - p.k_con) : p.con_normal_W);
      }
      J.block<3, 1>(0, j) = drn / p.Fc;
      J.block<3, 1>(3, j) = drm / (p.Fc * p.L);
      if (p.n_con == 3) J.block<3, 1>(p.k_con, j) = Vec3(yj + kP) / p.L;
      if (p.n_con == 1) J(p.k_con, j) = p.con_normal_W.dot(Vec3(yj + kP)) / p.L;
    }
  }

  void reduce_unknowns(Eigen::VectorXd&) const override {}
  void embed_unknowns(Eigen::VectorXd&) const override {}
  void embed_state(const Eigen::VectorXd& y, Eigen::VectorXd& y3) const override { y3 = y; }
};

}  // namespace

std::unique_ptr<Layout> make_3d_layout() { return std::make_unique<Layout3d>(); }

}  // namespace tcasim::cosserat::internal
