#pragma once
/// Kelvin-Voigt damping of the FE dynamics (docs/conventions.md "Beam FE dynamics"): at every
/// quadrature point the stress n = K_se e + B_se e_t, m = K_bt (omega - omega*) + B_bt omega_t,
/// with B_se = diag(eta_s A, eta_s A, eta A), B_bt = diag(eta I_x, eta I_y, eta_s J) at the
/// point's s (eta a constant or the body's viscosity profile, A, I, J the section there) and the
/// strain rate of the time step given by the Newmark relations of the generalized-alpha method
/// applied to the point's strains eps = (nu - e3, omega):
///   eps_t(n+1) = c_e (eps(n+1) - eps(n)) + h_n,  c_e = gamma / (beta dt),
///   h_n = (1 - gamma / beta) eps_t(n) + dt (1 - gamma / (2 beta)) a_eps(n),
/// (a_eps the strains' generalized-alpha acceleration variable). The viscous stress
/// sigma = B eps_t(n+1) = c_e B eps(n+1) + B (h_n - c_e eps(n)) is the gradient of the work
/// function W(eps) = sigma_h . eps + c_e/2 eps . B eps (sigma_h = B (h_n - c_e eps(n)) fixed during
/// the step): its nodal forces and their exact tangent (the added stiffness c_e B and the
/// geometric part of sigma) are what this class adds to the elastic residual.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <utility>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dynamics.hpp"

namespace tcasim::beam_fe::damping {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// Kelvin-Voigt viscosity eta at s [Pa s]: `override_Pa_s` when given (constant along s), else
/// the model's body.material.viscosity_Pa_s (a constant or a profile along s).
double viscosity_at(const rod::RodModel& model, double s_m,
                    const std::optional<double>& override_Pa_s);

/// Nodal forces int D^T sigma ds of the stress sigma = sigma_h + C eps per quadrature point
/// (C = diag(stiffness), 6 per point, in Discretization::strains order; C = 0: a fixed stress)
/// and, with K, their tangent under R <- R exp(eta), p <- p + dp, added into r (dof order of
/// Discretization) and K.
void add_viscous_forces(const Discretization& disc, const State& state,
                        const std::vector<Vector6d>& sigma_h,
                        const std::vector<Vector6d>& stiffness, Eigen::VectorXd& r,
                        Eigen::SparseMatrix<double>* K);

/// The strain history of every quadrature point and its viscous stress.
class StrainRateHistory {
 public:
  /// `disc` must outlive this object; the viscosity of viscosity_at(model, s, override).
  StrainRateHistory(const Discretization& disc, const rod::RodModel& model,
                    const std::optional<double>& viscosity_override_Pa_s, const AlphaParameters& ap,
                    double dt_s);
  /// At rest in `state`: eps(0) from the state, eps_t = a_eps = 0.
  void reset(const State& state);
  /// Adds the viscous forces (and their tangent) at the trial state.
  void add_forces(const State& trial, Eigen::VectorXd& r, Eigen::SparseMatrix<double>* K) const;
  /// Largest entries of the added stiffness c_e B over the points: of c_e B_se [N] and of
  /// c_e B_bt [N m^2] (for the round-off floor, Discretization::round_off_floor).
  std::pair<double, double> max_added_stiffness() const;
  /// The step to `state` converged: eps, eps_t, a_eps move to n + 1.
  void advance(const State& state);
  /// Sets the size of the following steps [s] (> 0): c_e = gamma / (beta dt) and c_e B anew;
  /// the history eps, eps_t, a_eps is kept (generalized-alpha is a one-step method).
  void set_time_step(double dt_s);

  /// The history of every point (what advance changes), to return to it (undo of a step).
  struct Snapshot {
    std::vector<Vector6d> eps, eps_t, a_eps;
  };
  Snapshot snapshot() const { return {eps_, eps_t_, a_eps_}; }
  void restore(const Snapshot& s) {
    eps_ = s.eps;
    eps_t_ = s.eps_t;
    a_eps_ = s.a_eps;
  }

 private:
  std::vector<Vector6d> strains(const State& state) const;
  Vector6d history(std::size_t k) const;  // h_n of point k
  const Discretization& disc_;
  AlphaParameters ap_;
  double h_, c_e_;
  std::vector<Vector6d> B_;   // per point diag(B_se, B_bt)
  std::vector<Vector6d> cB_;  // c_e B
  std::vector<Vector6d> eps_, eps_t_, a_eps_;
};

}  // namespace tcasim::beam_fe::damping
