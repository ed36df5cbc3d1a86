#include "cosserat/problem.hpp"

#include "cosserat/planar.hpp"

namespace tcasim::cosserat::internal {

RodProblem::RodProblem(const rod::RodModel& m, bool planar_layout)
    : model(m), planar(planar_layout) {
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
}

int RodProblem::state_dimension(const rod::RodModel& m, bool planar_state) {
  return (planar_state ? planar::kDelta : state_layout::kDelta) +
         static_cast<int>(m.actuators.size());
}

}  // namespace tcasim::cosserat::internal
