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

}  // namespace tcasim::rod
