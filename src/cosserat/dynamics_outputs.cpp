// Rod dynamics: energies, tensions and elongations of the last converged solve.
#include "cosserat/internal/dynamics_impl.hpp"

namespace tcasim::cosserat {

using namespace dynamics_names;

double RodDynamics::kinetic_energy_J() const {
  const Impl& d = *impl_;
  // RK4's weights over each step's stages: the same order in s as the states.
  double T = 0.0;
  for (int i = 0; i < d.N; ++i) {
    for (int j = 0; j < 4; ++j) {
      const PointData& x = d.cur[4 * i + j];
      const dynamics::SectionAt& sec = d.section_of(4 * i + j);
      T += d.stage_b[j] * d.step_length(i) * 0.5 *
           (sec.rho_A * x.q.squaredNorm() + x.w.dot(sec.rho_J.cwiseProduct(x.w)));
    }
  }
  return T + 0.5 * d.tip_mass_kg * d.cur[4 * d.N].q.squaredNorm();
}

double RodDynamics::potential_energy_J() const {
  const Impl& d = *impl_;
  double U = 0.0;
  for (int i = 0; i < d.N; ++i) {
    for (int j = 0; j < 4; ++j) {
      const PointData& x = d.cur[4 * i + j];
      const dynamics::SectionAt& sec = d.section_of(4 * i + j);
      const Vec3 dom = x.omega - sec.omega_star;
      U += d.stage_b[j] * d.step_length(i) *
           (0.5 * x.e.dot(sec.K_se.cwiseProduct(x.e)) + 0.5 * dom.dot(sec.K_bt.cwiseProduct(dom)) -
            (sec.rho_A * d.g_W).dot(x.p));
    }
  }
  const Eigen::VectorXd& tip = d.grid_converged.back();
  U -= (d.F_tip_W + d.tip_mass_kg * d.g_W).dot(tip.segment<3>(kP));
  for (int i = 0; i < d.n_act; ++i) {
    const double cT = d.tca_slot[i] >= 0 ? d.count[i] * tip[d.kT + d.tca_slot[i]] : d.cT[i];
    U += cT * tip[kDelta + i];
  }
  return U;
}

std::vector<double> RodDynamics::tensions_N() const {
  std::vector<double> t(impl_->n_act);
  for (int i = 0; i < impl_->n_act; ++i) {
    const int j = impl_->tca_slot[i];
    t[i] = j >= 0 ? impl_->grid_converged.front()[impl_->kT + j] : impl_->cT[i] / impl_->count[i];
  }
  return t;
}

std::vector<double> RodDynamics::elongations_m() const {
  std::vector<double> e(impl_->n_act);
  for (int i = 0; i < impl_->n_act; ++i) e[i] = impl_->grid_converged.back()[kDelta + i];
  return e;
}

std::vector<std::vector<double>> RodDynamics::segment_temperatures_K() const {
  std::vector<std::vector<double>> T(impl_->n_act);
  for (int i = 0; i < impl_->n_act; ++i) {
    if (impl_->tca_slot[i] < 0) continue;
    for (const tca::Segment& sg : impl_->segments[i]) T[i].push_back(sg.temperature_K);
  }
  return T;
}

}  // namespace tcasim::cosserat
