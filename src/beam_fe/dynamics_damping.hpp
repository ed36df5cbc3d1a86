#pragma once
/// Kelvin-Voigt damping of the FE dynamics (docs/conventions.md "Beam FE dynamics"): at every
/// quadrature point the stress n = K_se e + B_se e_t, m = K_bt (omega - omega*) + B_bt omega_t,
/// with the strain rate of the time step given by the Newmark relations of the
/// generalized-alpha method applied to the point's strains eps = (nu - e3, omega):
///   eps_t(n+1) = c_e (eps(n+1) - eps(n)) + h_n,  c_e = gamma / (beta dt),
///   h_n = (1 - gamma / beta) eps_t(n) + dt (1 - gamma / (2 beta)) a_eps(n),
/// (a_eps the strains' generalized-alpha acceleration variable). The part c_e B eps(n+1) is an
/// added stiffness (the dynamic discretization's model has E + c_e eta, G + c_e eta_s); the
/// rest is a stress sigma_h = B (c_e (eps* - eps(n)) + h_n) fixed during the step, whose nodal
/// forces D^T sigma_h and geometric tangent this class adds.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dynamics.hpp"

namespace tcasim::beam_fe::damping {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Nodal forces int D^T sigma ds of a fixed stress sigma per quadrature point (6 per point, in
/// Discretization::strains order) and, with K, their tangent under R <- R exp(eta) (the
/// geometric stiffness of sigma), added into r (dof order of Discretization) and K.
void add_fixed_stress_forces(const Discretization& disc, const State& state,
                             const std::vector<Vector6d>& sigma, Eigen::VectorXd& r,
                             Eigen::SparseMatrix<double>* K);

/// The strain history of every quadrature point and its stress sigma_h.
class StrainRateHistory {
 public:
  /// `disc` must outlive this object; eta the viscosity [Pa s], model the undamped model.
  StrainRateHistory(const Discretization& disc, const rod::RodModel& model, double eta_Pa_s,
                    const AlphaParameters& ap, double dt_s);
  /// At rest in `state`: eps(0) from the state, eps_t = a_eps = 0.
  void reset(const State& state);
  /// Adds the forces of sigma_h (and their tangent) at the trial state.
  void add_history_forces(const State& trial, Eigen::VectorXd& r,
                          Eigen::SparseMatrix<double>* K) const;
  /// The step to `state` converged: eps, eps_t, a_eps move to n + 1.
  void advance(const State& state);

 private:
  std::vector<Vector6d> strains(const State& state) const;
  const Discretization& disc_;
  AlphaParameters ap_;
  double h_, c_e_;
  Vector6d B_;                     // diag(B_se, B_bt)
  std::vector<Vector6d> eps_ref_;  // (0, omega*) per point
  std::vector<Vector6d> eps_, eps_t_, a_eps_;
};

}  // namespace tcasim::beam_fe::damping
