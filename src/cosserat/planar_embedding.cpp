// The planar reduction (cosserat/planar.hpp) seen from the 3-D solver: when it applies, and
// its unknowns and IVP states mapped to and from the 3-D layout of cosserat/shooting.hpp.
#include "cosserat/planar.hpp"
#include "cosserat/shooting_impl.hpp"

namespace tcasim::cosserat {

using namespace state_layout;
using internal::all_finite;
using internal::Mat3;
using internal::Vec3;
using internal::Vec6;

bool ShootingSolver::Impl::planar_model(const rod::RodModel& m, const Options& o) {
  if (!o.planar_reduction || !ode::is_fixed_step(o.integrator.method) ||
      o.kinematics != Kinematics::kFlat || o.jacobian != JacobianMethod::kSensitivity ||
      m.tip_constraint || static_cast<int>(m.actuators.size()) > planar::kMaxActuators) {
    return false;
  }
  // The planar right-hand sides have constant properties: a body that varies along s is
  // solved in 3-D (its pieces and jumps are RodRhs's).
  if (!m.uniform_body() || m.has_inner_anchors()) return false;
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

bool ShootingSolver::Impl::planar_loads(const Actuation& act) const {
  const Mat3& R0 = model.R_WB0;
  return R0.col(1).dot(act.gravity_W_m_s2) == 0.0 && R0.col(1).dot(act.tip_force_W_N) == 0.0 &&
         R0.col(0).dot(act.tip_moment_W_Nm) == 0.0 && R0.col(2).dot(act.tip_moment_W_Nm) == 0.0;
}

Summary ShootingSolver::Impl::solve_planar(Impl& p, const Actuation& act, Solution& sol) {
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

Eigen::VectorXd ShootingSolver::Impl::reduce(const Eigen::VectorXd& x3) const {
  Eigen::VectorXd x(nx);
  x << x3[0], x3[2], x3[4], x3.segment(6, n_tca);
  return x;
}

bool ShootingSolver::Impl::in_plane(const Eigen::VectorXd& x3) {
  return x3[1] == 0.0 && x3[3] == 0.0 && x3[5] == 0.0;
}

Eigen::VectorXd ShootingSolver::Impl::embed_unknowns(const Eigen::VectorXd& x) const {
  Eigen::VectorXd x3(6 + n_tca);
  x3 << x[0], 0.0, x[1], 0.0, x[2], 0.0, x.tail(n_tca);
  return x3;
}

Eigen::VectorXd ShootingSolver::Impl::embed_state(const Eigen::VectorXd& yp) const {
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

}  // namespace tcasim::cosserat
