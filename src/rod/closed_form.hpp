#pragma once
/// The closed form shared by both rod solvers' initial guesses (docs/conventions.md
/// "Closed form (straight strings, constant offsets, uniform tensions, no gravity)" and
/// "Initial guess (cold shooting solves)"): the constant strains of straight strings under
/// given tensions, the TCA tensions that solve the TCA law at the closed-form elongations,
/// and the TCA temperature ramp of the load continuation. Each solver keeps its own
/// discretization and nonlinear strategy; only this guess math is shared.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rod/model.hpp"
#include "tca/tca.hpp"

namespace tcasim::rod {

/// Constant strains of the closed form, offsets taken at s = 0.
struct ConstantStrains {
  Eigen::Vector3d e;      ///< nu - nu* (nu* = e_z), held as the deviation (no cancellation)
  Eigen::Vector3d omega;  ///< omega* plus its deviation [1/m]
};

/// nu_z - 1 = -sum c_i T_i / (E A), omega_x = omega*_x - sum c_i T_i r_i,y / (E I_x),
/// omega_y = omega*_y + sum c_i T_i r_i,x / (E I_y), others as the reference;
/// cT[i] = count_i T_i [N] for every actuator of `model`.
ConstantStrains closed_form_strains(const RodModel& model, const std::vector<double>& cT);
/// closed_form_strains with the base section's stiffnesses K_base = model.stiffness_at(0) and
/// reference curvature omega*(0) given by a caller that evaluates the closed form many times.
ConstantStrains closed_form_strains(const RodModel& model, const SectionStiffness& K_base,
                                    const Eigen::Vector3d& omega_star_base,
                                    const std::vector<double>& cT);

/// The closed form's string elongations, linear in the tensions:
///   delta_i = -L sum_j C_ij c_j T_j,  C_ij = 1/(E A) + r_i,y r_j,y / (E I_x) + r_i,x r_j,x / (E
///   I_y)
/// [m], cT as in closed_form_strains.
std::vector<double> closed_form_elongations_m(const RodModel& model, const std::vector<double>& cT);

/// The continuation's TCA temperature at load factor lambda: the material's reference
/// temperature T_ref at lambda = 0, the target at 1, T_ref + lambda (T - T_ref) between
/// (not clamped: the scenario reader requires T_ref inside the material's valid range).
inline double ramp_temperature_K(const tca::Material& material, double target_K, double lambda) {
  const double t_ref = material.reference_temperature_K;
  return t_ref + lambda * (target_K - t_ref);
}

/// The segments of a TCA drive at load factor lambda (ramp_temperature_K on each), written
/// into `out` (no allocation once `out` has the size).
void ramp_segments(const tca::Material& material, const std::vector<tca::Segment>& targets,
                   double lambda, std::vector<tca::Segment>& out);

/// Options of solve_guess_tensions.
struct GuessTensionOptions {
  /// Stop when ||g||_inf <= max(tolerance_N, tolerance_rel ||g(T_start)||_inf).
  double tolerance_N = 0.0;
  double tolerance_rel = 0.0;
  int max_iterations = 30;  ///< Newton steps
  int max_halvings = 30;    ///< backtracking halvings per step
  /// model.stiffness_at(0), when the caller has it (else evaluated once per call).
  std::optional<SectionStiffness> base_stiffness;
};

/// TCA tensions of the guess: with tca_actuators = indices k of the TCA drives and
/// segments[i] the (ramped) segments of actuator i, solves
///   g_k(T) = phi_k(T_k, delta_k(T)) = 0   (the TCA law with coil contact,
///   tca::contact_residual), delta_k = L |nu + omega x r_k + r_k'| - rest_k
/// at s = 0, with (nu - nu*, omega) the closed-form strains of cT plus `extra`
/// (head: strain, tail: curvature). Damped Newton on the exact derivative of delta: a step
/// is accepted when ||g||_2 decreases (out-of-domain trials count as rejected); a step that
/// cannot be accepted ends the iteration. T holds the start on entry (one entry per TCA)
/// and the last iterate on return; cT holds the known c T of the other actuators and, on
/// return, c T of the TCAs. Returns false if an evaluation at an accepted point fails
/// (DomainError or non-finite) or T is not finite; true otherwise (also when the tolerance
/// was not reached).
bool solve_guess_tensions(const RodModel& model, const std::vector<int>& tca_actuators,
                          const std::vector<std::vector<tca::Segment>>& segments,
                          const Eigen::Matrix<double, 6, 1>& extra,
                          const GuessTensionOptions& options, std::vector<double>& cT,
                          Eigen::VectorXd& T);

// --- Contact references (docs/validation.md "validate_contact") ---
//
// Closed forms of planar beams touching rigid obstacles, the references of the contact
// validation. All but the wrap are small-slope (Euler-Bernoulli, linear in w): their error
// against the geometrically exact rod is O(theta^2) relative, theta the largest slope
// (theta ~ H / l below), plus the rod's shear and extension, O((r / l)^2). B is the bending
// stiffness E I [N m^2]. Frictionless, so a touching surface pushes along its normal only.

/// A heavy rod (weight q per length) clamped horizontally at a gap H above a frictionless
/// floor, long enough to reach it: free span [0, l], the rest lying flat on the floor.
/// Clamped: EI w'''' = -q on (0, l), w(0) = H, w'(0) = 0; at touchdown w = w' = w'' = 0 (the
/// flat part has no curvature and no moment, so neither has the free span's end). With
/// xi = l - x: w = q l xi^3 / (18 B) - q xi^4 / (24 B), and w(xi = l) = H gives
///   l = (72 B H / q)^(1/4); shear jump at touchdown B w'''(0+) = q l / 3 (a point force,
///   the flat part carries its own weight by a pressure q); clamp force 2 q l / 3 up, clamp
///   moment q l^2 / 6 (= q l^2 / 2 - (q l / 3) l about the clamp); largest slope
///   q l^3 / (6 B) max xi^2 (l - xi) / l^3 = 2 q l^3 / (81 B) = 16 H / (9 l) at xi = 2 l / 3.
/// Pinned (a hinge at the base, M(0) = 0 instead of w'(0) = 0): w = q l xi^3 / (12 B) -
///   q xi^4 / (24 B), l = (24 B H / q)^(1/4), point force q l / 2, base force q l / 2, base
///   moment 0; largest slope q l^3 / (12 B) = 2 H / l at the hinge.
struct HeavyRodOnFloor {
  double free_span_m = 0.0;        ///< l: base to touchdown (horizontal, = s to first order)
  double touchdown_force_N = 0.0;  ///< the point force at touchdown (upward)
  double base_force_N = 0.0;       ///< the clamp's (hinge's) upward force on the free span
  double base_moment_Nm = 0.0;     ///< the clamp's moment magnitude (0 for the hinge)
  double max_slope = 0.0;          ///< largest |w'| of the free span (small-slope measure)
};
/// The clamped (pinned = false) or pinned heavy rod on a floor; B, q, H > 0 (DomainError
/// otherwise). The part of the body beyond l lies on the floor: a rod shorter than l does
/// not reach it (the caller checks l < L).
HeavyRodOnFloor heavy_rod_on_floor(double B_N_m2, double q_N_m, double H_m, bool pinned = false);

/// Deflection of the clamped (or pinned) heavy rod's free span at x in [0, l] (height above
/// the floor, w(0) = H), of heavy_rod_on_floor's closed form; 0 beyond l.
double heavy_rod_on_floor_height_m(double B_N_m2, double q_N_m, double H_m, double x_m,
                                   bool pinned = false);

/// A cantilever of length L clamped tangent to a rigid cylinder of radius R (L << R, small
/// slope) with a tip force F toward it. Free, w = -F x^2 (3 L - x) / (6 B) has the clamp
/// curvature F L / B, which reaches the cylinder's 1 / R at F = B / (R L): contact onset.
/// Beyond, the rod lies on the cylinder over [0, a] (curvature 1 / R, constant moment B / R,
/// no shear, so no pressure) and leaves it where the free part's moment F (L - x) falls
/// below B / R: free length c = B / (F R), a = L - c, and the cylinder pushes with one point
/// force F at the lift-off x = a (the shear jumps from F to 0); the clamp holds the moment
/// B / R and no force. Tip deflection toward the cylinder a^2 / (2 R) + a c / R + F c^3 /
/// (3 B) = L^2 / (2 R) - B^2 / (6 F^2 R^3) (free: F L^3 / (3 B)).
struct CantileverOnCylinder {
  double onset_force_N = 0.0;     ///< B / (R L)
  bool touching = false;          ///< F > onset
  double lift_off_m = 0.0;        ///< a (0 when not touching)
  double contact_force_N = 0.0;   ///< F at the lift-off (0 when not touching)
  double tip_deflection_m = 0.0;  ///< toward the cylinder, from the straight rod
  double clamp_moment_Nm = 0.0;   ///< F L free, B / R touching
};
/// B, L, R > 0, F >= 0 (DomainError otherwise).
CantileverOnCylinder cantilever_on_cylinder(double B_N_m2, double L_m, double R_m, double F_N);

/// Propped cantilever: a cantilever of length L with a tip force P, held by a point support
/// at x = a in (0, L] at its unloaded height. The support's deflection from P,
/// P a^2 (3 L - a) / (6 B), cancels that of the reaction, R a^3 / (3 B):
///   R = P (3 L - a) / (2 a)   (R = P at a = L; independent of B).
/// L > 0, 0 < a <= L (DomainError otherwise).
double propped_cantilever_reaction_N(double P_N, double L_m, double a_m);

/// A rod pulled over a frictionless cylinder by end tensions T (geometrically exact elastica;
/// rho = R + r, the centerline radius on the cylinder). On the arc the curvature is 1 / rho,
/// the moment B / rho constant, so there is no shear and the internal force is axial, N, with
/// the pressure N / rho. Each free part carries the constant force T along its far direction
/// and is an elastica under tension, B theta'^2 / 2 = T (1 - cos theta) (theta from the far
/// direction, straight far away); at lift-off its curvature is 1 / rho:
///   cos theta_d = 1 - B / (2 T rho^2),
/// the force T there has the tangential part T cos theta_d = N (so N = T - B / (2 rho^2)) and
/// the normal part T sin theta_d: a point force at each lift-off. An arc exists only where
/// this angle is defined, T >= B / (4 rho^2) (theta_d <= pi), and where it is shorter than
/// the wrap: arc angle = wrap angle (between the two far directions) - 2 theta_d > 0.
struct WrapOnCylinder {
  double lift_off_angle_rad = 0.0;  ///< theta_d
  double point_force_N = 0.0;       ///< T sin theta_d at each lift-off
  double axial_force_N = 0.0;       ///< N = T - B / (2 rho^2) on the arc
  double pressure_N_m = 0.0;        ///< N / rho
};
/// None when T < B / (4 rho^2) (no arc); B, rho > 0, T >= 0 (DomainError otherwise).
std::optional<WrapOnCylinder> rod_wrapped_on_cylinder(double B_N_m2, double T_N, double rho_m);

}  // namespace tcasim::rod
