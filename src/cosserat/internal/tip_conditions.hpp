#pragma once
/// The shooting residual r(x) at the tip (docs/conventions.md "Tip conditions", documented
/// at the top of cosserat/shooting.hpp): the tip force and moment balance, the TCA rows with
/// coil contact, the tip-constraint rows, their scaling by the characteristic force F_c, the
/// chain rule from the IVP's forward sensitivities to dr/dx, and the global equilibrium
/// check of a solution. Internal to the shooting solver.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "cosserat/internal/rhs.hpp"
#include "cosserat/shooting.hpp"

namespace tcasim::cosserat::internal {

struct TipConditions : RodRhs {
  TipConditions(const rod::RodModel& m, std::unique_ptr<Layout> layout, bool sensitivities);

  // docs/conventions.md "Tip conditions" (body frame), scaled.
  /// Scaled residual r (size nx) at unknowns x with y(L) = yL; cT and the scaled segments
  /// set for x (RodRhs::set_parameters): the layout's tip rows (Layout::tip_rows) and the
  /// TCA rows. False when a TCA law fails or r is not finite.
  bool tip_residual(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& yL, Eigen::VectorXd& r);
  /// TCA rows r_k = phi(T_k, delta_k(L)) / F_c (tca::contact_residual: the free-coil law
  /// T_k - F_tca(delta_k) with coil contact) with delta at yL[delta0 + i]; sets dphi_dT and
  /// dphi_ddelta. False when a TCA law fails or r is not finite.
  bool tca_rows(const Eigen::VectorXd& x, const Eigen::VectorXd& yL, Eigen::VectorXd& r);
  /// dr/dx (nx x nx) at x from y(L) = y and the augmented state Y(L) = (y, dy/dx_0, ...)
  /// of the sensitivity IVP (chain rule: dr = (dr/dy) Y(L) + dr/dT), after tip_residual at
  /// the same point (its dphi_dT, dphi_ddelta): the layout's tip rows
  /// (Layout::tip_rows_jacobian) and the TCA rows. False when J is not finite.
  bool tip_jacobian(const rod::Loads& act, double lambda, const Eigen::VectorXd& x,
                    const Eigen::VectorXd& y, const Eigen::VectorXd& Y, Eigen::MatrixXd& J) const;
  /// Tip force the holder applies to the rod (world frame) for unknowns x; 0 without a
  /// tip constraint.
  Vec3 reaction_W(const Eigen::VectorXd& x) const;
  /// Global equilibrium (docs/conventions.md): n(0), m(0) of the 3-D unknowns x against the
  /// applied loads, with yL = y(L) (3-D layout) and cT, f_ext_W set for x at full load.
  void equilibrium(const rod::Loads& act, const Eigen::VectorXd& x, const Eigen::VectorXd& yL,
                   Summary& summary) const;

  /// Characteristic force F_c [N] of the residual scaling (shooting.hpp).
  double Fc = 1.0;
  // Per actuator, at the last tip residual (TCA drives): the derivatives of the contact
  // residual phi(T, delta) (tca::contact_residual); the TCA row is phi / F_c.
  std::vector<double> dphi_dT;
  std::vector<double> dphi_ddelta;
};

}  // namespace tcasim::cosserat::internal
