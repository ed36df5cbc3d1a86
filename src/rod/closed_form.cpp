#include "rod/closed_form.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace tcasim::rod {
namespace {

/// closed_form_strains with the base section's stiffnesses K and reference curvature omega*.
ConstantStrains strains_of(const RodModel& model, const SectionStiffness& K,
                           const Eigen::Vector3d& omega_star, const std::vector<double>& cT) {
  const Eigen::Vector3d& K_nu = K.shear_extension;
  const Eigen::Vector3d& K_omega = K.bending_torsion;
  double sum_T = 0.0, sum_Tx = 0.0, sum_Ty = 0.0;
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    // A string anchored inside the body (span_m) has no share of the base wrench.
    if (model.actuators[i].span_start_m() > 0.0) continue;
    const Eigen::Vector3d r = model.actuators[i].routing.r(0.0);
    sum_T += cT[i];
    sum_Tx += cT[i] * r.x();
    sum_Ty += cT[i] * r.y();
  }
  // docs/conventions.md "Closed form": the moment sum c T r x e_z balances K_omega (omega -
  // omega*), the force sum c T e_z balances K_nu (nu - nu*).
  ConstantStrains s;
  s.e = Eigen::Vector3d(0.0, 0.0, -sum_T / K_nu.z());
  s.omega = omega_star + Eigen::Vector3d(-sum_Ty / K_omega.x(), sum_Tx / K_omega.y(), 0.0);
  return s;
}

}  // namespace

ConstantStrains closed_form_strains(const RodModel& model, const std::vector<double>& cT) {
  return strains_of(model, model.stiffness_at(0.0), model.reference_curvature_at(0.0), cT);
}

ConstantStrains closed_form_strains(const RodModel& model, const SectionStiffness& K_base,
                                    const Eigen::Vector3d& omega_star_base,
                                    const std::vector<double>& cT) {
  return strains_of(model, K_base, omega_star_base, cT);
}

std::vector<double> closed_form_elongations_m(const RodModel& model,
                                              const std::vector<double>& cT) {
  const SectionStiffness K = model.stiffness_at(0.0);
  const Eigen::Vector3d& K_nu = K.shear_extension;
  const Eigen::Vector3d& K_omega = K.bending_torsion;
  std::vector<double> delta(model.actuators.size(), 0.0);
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const Eigen::Vector3d ri = model.actuators[i].routing.r(0.0);
    const double span = model.actuators[i].span_end_m(model.length_m) -
                        model.actuators[i].span_start_m();  // L without span_m
    for (std::size_t j = 0; j < model.actuators.size(); ++j) {
      if (model.actuators[j].span_start_m() > 0.0) continue;  // not in the base wrench
      const Eigen::Vector3d rj = model.actuators[j].routing.r(0.0);
      const double C =
          1.0 / K_nu.z() + ri.y() * rj.y() / K_omega.x() + ri.x() * rj.x() / K_omega.y();
      delta[i] -= span * C * cT[j];
    }
  }
  return delta;
}

void ramp_segments(const tca::Material& material, const std::vector<tca::Segment>& targets,
                   double lambda, std::vector<tca::Segment>& out) {
  out = targets;
  for (tca::Segment& seg : out)
    seg.temperature_K = ramp_temperature_K(material, seg.temperature_K, lambda);
}

bool solve_guess_tensions(const RodModel& model, const std::vector<int>& tca_actuators,
                          const std::vector<std::vector<tca::Segment>>& segments,
                          const Eigen::Matrix<double, 6, 1>& extra,
                          const GuessTensionOptions& options, std::vector<double>& cT,
                          Eigen::VectorXd& T) {
  const int n = static_cast<int>(tca_actuators.size());
  if (n == 0) return true;
  const double L = model.length_m;
  // The base section's properties, evaluated once for every evaluation of g below.
  const SectionStiffness K =
      options.base_stiffness ? *options.base_stiffness : model.stiffness_at(0.0);
  const Eigen::Vector3d& K_nu = K.shear_extension;
  const Eigen::Vector3d& K_omega = K.bending_torsion;
  const Eigen::Vector3d omega_star = model.reference_curvature_at(0.0);
  const Eigen::Vector3d nu_star = Eigen::Vector3d::UnitZ();
  Eigen::VectorXd g(n), gt(n), dT(n), Tt(n);
  Eigen::MatrixXd G(n, n);
  // g_k at tensions Tk (it may throw DomainError), with its Jacobian when Gk is non-null:
  //   dg_k/dT_l = dphi_k/dF delta_kl + dphi_k/d delta L qh_k . c_l (dnu_l + domega_l x r_k),
  //   dnu_l = -e_z / (E A), domega_l = (-r_l,y / (E I_x), r_l,x / (E I_y), 0)   (closed form).
  auto eval = [&](const Eigen::VectorXd& Tk, Eigen::VectorXd& gk, Eigen::MatrixXd* Gk) {
    for (int k = 0; k < n; ++k) {
      const int i = tca_actuators[k];
      cT[i] = model.actuators[i].count * Tk[k];
    }
    const ConstantStrains cf = strains_of(model, K, omega_star, cT);
    const Eigen::Vector3d nu = nu_star + cf.e + extra.head<3>();
    const Eigen::Vector3d omega = cf.omega + extra.tail<3>();
    for (int k = 0; k < n; ++k) {
      const int i = tca_actuators[k];
      const Actuator& act = model.actuators[i];
      const Eigen::Vector3d r = act.routing.r(0.0);
      const Eigen::Vector3d q = nu + omega.cross(r) + act.routing.dr(0.0);
      // The base section's strains over the string's span (L without span_m).
      const double span = act.span_end_m(L) - act.span_start_m();
      const double delta = span * q.norm() - act.rest_length_m;
      const tca::ContactResidual c =
          tca::contact_residual(*act.drive.tca, Tk[k], delta, segments[i]);
      gk[k] = c.phi_N;
      if (Gk) {
        const Eigen::Vector3d qh = q.normalized();
        for (int l = 0; l < n; ++l) {
          const Actuator& al = model.actuators[tca_actuators[l]];
          if (al.span_start_m() > 0.0) {  // not in the base wrench (closed_form_strains)
            (*Gk)(k, l) = k == l ? c.dphi_dF : 0.0;
            continue;
          }
          const Eigen::Vector3d rl = al.routing.r(0.0);
          const Eigen::Vector3d dnu(0.0, 0.0, -al.count / K_nu.z());
          const Eigen::Vector3d domega(-al.count * rl.y() / K_omega.x(),
                                       al.count * rl.x() / K_omega.y(), 0.0);
          (*Gk)(k, l) =
              (k == l ? c.dphi_dF : 0.0) + c.dphi_ddelta_N_m * span * qh.dot(dnu + domega.cross(r));
        }
      }
    }
    return gk.allFinite();
  };
  bool ok = false;
  try {
    ok = eval(T, g, &G);
    const double tolerance =
        std::max(options.tolerance_N, options.tolerance_rel * g.lpNorm<Eigen::Infinity>());
    for (int it = 0; ok && it < options.max_iterations && g.lpNorm<Eigen::Infinity>() > tolerance;
         ++it) {
      dT = G.partialPivLu().solve(-g);
      if (!dT.allFinite()) break;
      double t = 1.0;
      bool accepted = false;
      for (int ls = 0; ls < options.max_halvings && !accepted; ++ls, t *= 0.5) {
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
  for (int k = 0; k < n; ++k) {
    const int i = tca_actuators[k];
    cT[i] = model.actuators[i].count * T[k];
  }
  return ok && T.allFinite();
}

namespace {

/// Throws DomainError naming the closed form and the quantity unless `ok`.
void require_domain(bool ok, const char* form, const char* what, double value) {
  if (!ok) {
    throw DomainError(std::string(form) + ": " + what + " = " + format_value(value) +
                      " is outside the closed form's domain");
  }
}

}  // namespace

HeavyRodOnFloor heavy_rod_on_floor(double B, double q, double H, bool pinned) {
  const char* form = "heavy_rod_on_floor";
  require_domain(B > 0.0 && std::isfinite(B), form, "B", B);
  require_domain(q > 0.0 && std::isfinite(q), form, "q", q);
  require_domain(H > 0.0 && std::isfinite(H), form, "H", H);
  HeavyRodOnFloor r;
  if (pinned) {
    r.free_span_m = std::pow(24.0 * B * H / q, 0.25);
    r.touchdown_force_N = 0.5 * q * r.free_span_m;
    r.base_force_N = 0.5 * q * r.free_span_m;
    r.base_moment_Nm = 0.0;
    r.max_slope = 2.0 * H / r.free_span_m;
  } else {
    r.free_span_m = std::pow(72.0 * B * H / q, 0.25);
    r.touchdown_force_N = q * r.free_span_m / 3.0;
    r.base_force_N = 2.0 * q * r.free_span_m / 3.0;
    r.base_moment_Nm = q * r.free_span_m * r.free_span_m / 6.0;
    r.max_slope = 16.0 * H / (9.0 * r.free_span_m);
  }
  return r;
}

double heavy_rod_on_floor_height_m(double B, double q, double H, double x, bool pinned) {
  const double l = heavy_rod_on_floor(B, q, H, pinned).free_span_m;
  if (x >= l) return 0.0;
  const double xi = l - std::max(x, 0.0);
  const double a = q * l / ((pinned ? 12.0 : 18.0) * B);
  return a * xi * xi * xi - q * xi * xi * xi * xi / (24.0 * B);
}

CantileverOnCylinder cantilever_on_cylinder(double B, double L, double R, double F) {
  const char* form = "cantilever_on_cylinder";
  require_domain(B > 0.0 && std::isfinite(B), form, "B", B);
  require_domain(L > 0.0 && std::isfinite(L), form, "L", L);
  require_domain(R > 0.0 && std::isfinite(R), form, "R", R);
  require_domain(F >= 0.0 && std::isfinite(F), form, "F", F);
  CantileverOnCylinder c;
  c.onset_force_N = B / (R * L);
  c.touching = F > c.onset_force_N;
  if (!c.touching) {
    c.tip_deflection_m = F * L * L * L / (3.0 * B);
    c.clamp_moment_Nm = F * L;
    return c;
  }
  const double free = B / (F * R);
  c.lift_off_m = L - free;
  c.contact_force_N = F;
  c.tip_deflection_m = L * L / (2.0 * R) - B * B / (6.0 * F * F * R * R * R);
  c.clamp_moment_Nm = B / R;
  return c;
}

double propped_cantilever_reaction_N(double P, double L, double a) {
  const char* form = "propped_cantilever_reaction_N";
  require_domain(L > 0.0 && std::isfinite(L), form, "L", L);
  require_domain(a > 0.0 && a <= L, form, "a", a);
  require_domain(std::isfinite(P), form, "P", P);
  return P * (3.0 * L - a) / (2.0 * a);
}

std::optional<WrapOnCylinder> rod_wrapped_on_cylinder(double B, double T, double rho) {
  const char* form = "rod_wrapped_on_cylinder";
  require_domain(B > 0.0 && std::isfinite(B), form, "B", B);
  require_domain(T >= 0.0 && std::isfinite(T), form, "T", T);
  require_domain(rho > 0.0 && std::isfinite(rho), form, "rho", rho);
  if (T < B / (4.0 * rho * rho)) return std::nullopt;
  WrapOnCylinder w;
  const double c = 1.0 - B / (2.0 * T * rho * rho);
  w.lift_off_angle_rad = std::acos(std::clamp(c, -1.0, 1.0));
  w.point_force_N = T * std::sin(w.lift_off_angle_rad);
  w.axial_force_N = T - B / (2.0 * rho * rho);
  w.pressure_N_m = w.axial_force_N / rho;
  return w;
}

}  // namespace tcasim::rod
