#pragma once
/// The body properties the rod dynamics reads at arc length s, in one place: stiffness,
/// Kelvin-Voigt damping, mass and rotational inertia per unit length, reference strains
/// (docs/conventions.md "Rod dynamics (shooting method)"). They follow the model's profiles
/// along s (docs/scenario-format.md "Profiles along the body"), viscosity included.
#include <Eigen/Core>
#include <algorithm>
#include <optional>
#include <vector>

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

/// Kelvin-Voigt viscosity eta at s [Pa s]: `override_Pa_s` when given (constant along s),
/// else the model's body.material.viscosity_Pa_s profile.
inline double viscosity_at(const rod::RodModel& model, double s_m,
                           const std::optional<double>& override_Pa_s,
                           rod::Side side = rod::Side::kRight) {
  if (override_Pa_s) return *override_Pa_s;
  return model.material.viscosity_profile.value(s_m, side);
}

/// Whether section_at() is the same at every s (then the solver evaluates it once).
inline bool section_is_uniform(const rod::RodModel& model,
                               const std::optional<double>& viscosity_override_Pa_s) {
  return model.uniform_body() &&
         (viscosity_override_Pa_s || model.material.viscosity_profile.is_constant());
}

/// The properties at arc length s [m] with Kelvin-Voigt viscosity eta [Pa s]
/// (eta_s = eta / (2 (1 + poisson_ratio)), as G from E); at a jump of a profile the limit
/// from `side`.
inline SectionAt section_at(const rod::RodModel& model, double s_m, double viscosity_Pa_s,
                            rod::Side side = rod::Side::kRight) {
  SectionAt p;
  const double eta = viscosity_Pa_s;
  const rod::SectionProperties sec = model.section.properties_at(s_m, side);
  const rod::MaterialProperties mat = model.material.properties_at(s_m, side);
  const rod::SectionStiffness K =
      rod::section_stiffness(sec, mat.youngs_modulus_Pa, mat.shear_modulus_Pa);
  const rod::SectionStiffness B =
      rod::section_stiffness(sec, eta, model.material.shear_modulus(eta));
  p.K_se = K.shear_extension;
  p.K_bt = K.bending_torsion;
  p.B_se = B.shear_extension;
  p.B_bt = B.bending_torsion;
  const double rho = mat.density_kg_m3;
  p.rho_A = rho * sec.area_m2;
  p.rho_J = Eigen::Vector3d(rho * sec.I_x_m4, rho * sec.I_y_m4, rho * (sec.I_x_m4 + sec.I_y_m4));
  p.omega_star = model.reference_curvature_at(s_m, side);
  return p;
}

/// The properties at s with the viscosity of viscosity_at().
inline SectionAt section_at(const rod::RodModel& model, double s_m,
                            const std::optional<double>& viscosity_override_Pa_s,
                            rod::Side side = rod::Side::kRight) {
  return section_at(model, s_m, viscosity_at(model, s_m, viscosity_override_Pa_s, side), side);
}

/// Where the dynamics' grid must have a node: every breakpoint of the model's profiles and of
/// the viscosity profile (unless overridden) strictly inside (0, L), sorted, without repeats.
inline std::vector<double> grid_breakpoints(const rod::RodModel& model,
                                            const std::optional<double>& viscosity_override_Pa_s) {
  std::vector<double> all = model.breakpoints();
  if (!viscosity_override_Pa_s) {
    for (double s : model.material.viscosity_profile.breakpoints()) {
      if (s > 0.0 && s < model.length_m) all.push_back(s);
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

}  // namespace tcasim::cosserat::dynamics
