#pragma once
/// The body properties the rod dynamics reads at arc length s, in one place: stiffness,
/// Kelvin-Voigt damping, mass and rotational inertia per unit length, reference strains
/// (docs/conventions.md "Rod dynamics (shooting method)"). Constant along s today (the
/// model's constant section and material); switching to properties that vary along s
/// changes only section_at().
#include <Eigen/Core>

#include "rod/model.hpp"

namespace tcasim::cosserat::dynamics {

/// Body properties at one arc length (body frame B, SI).
struct SectionAt {
  Eigen::Vector3d K_se;        ///< diag(G A, G A, E A) [N]
  Eigen::Vector3d K_bt;        ///< diag(E I_x, E I_y, G J) [N m^2]
  Eigen::Vector3d B_se;        ///< diag(eta_s A, eta_s A, eta A) [N s]
  Eigen::Vector3d B_bt;        ///< diag(eta I_x, eta I_y, eta_s J) [N m^2 s]
  double rho_A = 0.0;          ///< mass per unit length [kg/m]
  Eigen::Vector3d rho_J;       ///< rotational inertia per length diag(rho I_x, rho I_y,
                               ///< rho (I_x + I_y)) [kg m]
  Eigen::Vector3d omega_star;  ///< reference curvature [1/m]
};

/// The properties at arc length s [m] with Kelvin-Voigt viscosity eta [Pa s]
/// (eta_s = eta / (2 (1 + poisson_ratio)), as G from E).
inline SectionAt section_at(const rod::RodModel& model, double /*s_m*/, double viscosity_Pa_s) {
  SectionAt p;
  p.K_se = model.shear_extension_stiffness();
  p.K_bt = model.bending_torsion_stiffness();
  const double eta = viscosity_Pa_s;
  const double eta_s = eta / (2.0 * (1.0 + model.material.poisson_ratio));
  const rod::Section& sec = model.section;
  p.B_se = Eigen::Vector3d(eta_s * sec.area_m2, eta_s * sec.area_m2, eta * sec.area_m2);
  p.B_bt = Eigen::Vector3d(eta * sec.I_x_m4, eta * sec.I_y_m4, eta_s * sec.J_m4);
  const double rho = model.material.density_kg_m3;
  p.rho_A = rho * sec.area_m2;
  p.rho_J = Eigen::Vector3d(rho * sec.I_x_m4, rho * sec.I_y_m4, rho * (sec.I_x_m4 + sec.I_y_m4));
  p.omega_star = model.reference_curvature_B_1_m;
  return p;
}

/// Whether section_at() is the same at every s (then the solver evaluates it once).
inline bool section_is_uniform(const rod::RodModel& /*model*/) { return true; }

}  // namespace tcasim::cosserat::dynamics
