#include "cosserat/internal/problem.hpp"

#include <algorithm>

namespace tcasim::cosserat::internal {

RodProblem::RodProblem(const rod::RodModel& m, const LayoutDims& d)
    : model(m),
      x_tca(d.strain_unknowns),
      strain_offset(d.strain_offset),
      delta_offset(d.delta_offset) {
  n_act = static_cast<int>(model.actuators.size());
  dim = delta_offset + n_act;
  L = model.length_m;
  const rod::SectionStiffness K_base = model.stiffness_at(0.0);
  K_nu = K_base.shear_extension;
  K_omega = K_base.bending_torsion;
  K_nu_inv = K_nu.cwiseInverse();
  K_omega_inv = K_omega.cwiseInverse();
  nu_star = Vec3::UnitZ();
  omega_star = model.reference_curvature_at(0.0);
  unknown_of.assign(n_act, -1);
  for (int i = 0; i < n_act; ++i) {
    const rod::Actuator& a = model.actuators[i];
    if (a.drive.type == rod::Drive::Type::kTca) {
      unknown_of[i] = x_tca + n_tca++;
      act_of.push_back(i);
    }
    span_lo.push_back(a.span_start_m());
    span_hi.push_back(a.span_end_m(L));
    length_ratio.push_back(a.rest_length_m / (span_hi.back() - span_lo.back()));
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

  uniform = model.uniform_body();
  K_nu_tip = K_nu;
  K_omega_tip = K_omega;
  omega_star_tip = omega_star;
  density_base = model.material.density_profile.value(0.0);
  area_base = model.section.properties_at(0.0).area_m2;
  rho_A_ref = density_base * area_base;
  weight_length = L;
  if (!uniform) {
    K_nu_tip = model.shear_extension_stiffness(L, rod::Side::kLeft);
    K_omega_tip = model.bending_torsion_stiffness(L, rod::Side::kLeft);
    omega_star_tip = model.reference_curvature_at(L, rod::Side::kLeft);
    for (const rod::Profile& c : model.reference_curvature_profile) {
      omega_star_varies = omega_star_varies || (!c.is_constant() && c.min_value() != c.max_value());
    }
    knots = model.breakpoints();
    knots.push_back(0.0);
    knots.push_back(0.5 * L);  // a step node at L/2 (the bending radius samples it)
    knots.push_back(L);
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
    for (double s : knots) knot_jumps.push_back(model.jumps_at(s));
    // psi A is a polynomial between the knots (a linear diameter's quadratic area times a
    // linear density): its largest value at the knots (up to the bulge of a product of two
    // linear factors, which only sets a scale) and its integral by 8-point Gauss-Legendre
    // on each piece (exact to degree 15).
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                 -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                 0.7966664774136267,  0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                 0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                 0.2223810344533745, 0.1012285362903763};
    rho_A_ref = 0.0;
    for (std::size_t k = 0; k < knots.size(); ++k) {
      rho_A_ref = std::max({rho_A_ref, model.mass_per_length_kg_m(knots[k], rod::Side::kLeft),
                            model.mass_per_length_kg_m(knots[k], rod::Side::kRight)});
    }
    double mass = 0.0;
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      const double a = knots[k], b = knots[k + 1];
      for (int g = 0; g < 8; ++g)
        mass += 0.5 * (b - a) * gw[g] * model.mass_per_length_kg_m(0.5 * (a + b + (b - a) * gx[g]));
    }
    weight_length = rho_A_ref > 0.0 ? mass / rho_A_ref : L;
  }
  omega_star_tip_model = omega_star_tip;
  add_string_knots();
}

void RodProblem::set_omega_star_fraction(double mu) {
  omega_star_fraction = mu;
  omega_star_tip = omega_star_tip_model;
  if (mu != 1.0) omega_star_tip = homotopy_omega_star(omega_star_tip_model);
}

void RodProblem::properties(double s, rod::Side side, Vec3& Kn, Vec3& Kw, Vec3& ws,
                            double& wf) const {
  model_properties(s, side, Kn, Kw, ws, wf);
  if (omega_star_fraction != 1.0) ws = homotopy_omega_star(ws);
}

void RodProblem::model_properties(double s, rod::Side side, Vec3& Kn, Vec3& Kw, Vec3& ws,
                                  double& wf) const {
  const rod::SectionStiffness K = model.stiffness_at(s, side);
  Kn = K.shear_extension;
  Kw = K.bending_torsion;
  ws = model.reference_curvature_at(s, side);
  wf = rho_A_ref > 0.0 ? model.mass_per_length_kg_m(s, side) / rho_A_ref : 1.0;
}

}  // namespace tcasim::cosserat::internal
