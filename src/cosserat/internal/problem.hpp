#pragma once
/// The constant data of one shooting problem, fixed when the solver is built: the layout of
/// the IVP state and of the unknowns (3-D, or the planar reduction's), the stiffnesses and
/// the per-actuator constants. Internal to the shooting solver (cosserat/shooting.hpp
/// documents the layouts).
#include <Eigen/Core>
#include <vector>

#include "cosserat/internal/layout.hpp"
#include "cosserat/internal/string_system.hpp"
#include "cosserat/shooting.hpp"
#include "rod/model.hpp"

namespace tcasim::cosserat::internal {

/// Forward sensitivities keep their 6 x nx work matrix on the stack: at most this many
/// unknowns (10 TCA drives); beyond, the solver uses forward differences instead.
inline constexpr int kMaxSensitivityUnknowns = 16;

inline bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

struct RodProblem {
  /// d: the sizes of the layout (cosserat/internal/layout.hpp: 3-D or the planar reduction's).
  RodProblem(const rod::RodModel& m, const LayoutDims& d);

  const rod::RodModel& model;
  int x_tca = 6;  // index of the first TCA unknown: after the strain unknowns of the layout
  int strain_offset = state_layout::kNu;    // index in y of the strains x[0, x_tca) set
  int delta_offset = state_layout::kDelta;  // index of delta_0 in y
  int n_act = 0;
  int n_tca = 0;
  int nx = 0;
  // Tip constraint (RodModel::tip_constraint): n_con = 3 (pinned) or 1 (normal only)
  // reaction unknowns at x[k_con...] and as many position residuals at r[k_con...].
  int n_con = 0;
  int k_con = 0;
  Vec3 con_target_W = Vec3::Zero();
  Vec3 con_normal_W = Vec3::Zero();
  int dim = 0;
  double L = 0.0;
  Vec3 K_nu, K_omega, nu_star, omega_star;
  Vec3 K_nu_inv, K_omega_inv;   // reciprocals for StringSystem
  std::vector<int> unknown_of;  // actuator -> unknown index (-1 for tension drives)
  std::vector<int> act_of;      // TCA unknown k (x[x_tca + k]) -> actuator
  std::vector<double> length_ratio;
  std::vector<double> count;
  std::vector<bool> straight;

  // A body whose properties vary along s (rod::RodModel::uniform_body() false): the members
  // K_nu, K_omega, omega_star above hold the values at s = 0 (initial guess, scales), the
  // *_tip ones those at s = L (tip conditions), and the IVP is integrated piece by piece
  // between `knots` (0, every breakpoint of the profiles, L/2, L). For a uniform body the tip
  // values equal the base ones and knots is empty.
  bool uniform = true;
  std::vector<double> knots;
  std::vector<bool> knot_jumps;  // per knot: whether a property jumps there
  Vec3 K_nu_tip, K_omega_tip, omega_star_tip;
  /// The weight per length is f_ext_W times weight_factor(s) = psi A(s) / psi A_ref (psi A_ref:
  /// the largest psi A along s; 1 for a uniform body), and weight_length = int_0^L of it
  /// (L for a uniform body).
  double rho_A_ref = 0.0;
  double weight_length = 0.0;
  /// psi and A at s = 0, evaluated once: a uniform body's f_ext_W is lambda psi A g.
  double density_base = 0.0, area_base = 0.0;
  // Strings anchored inside the body (rod::Actuator::span_m; cosserat/string_jumps.cpp): the
  // anchors are knots too (a uniform body with anchors has knots 0, L/2, L and the anchors),
  // a jump there moves the string's share of the section wrench to the rod, and
  // string_runs[piece][i] says whether string i runs along piece [knots[piece],
  // knots[piece + 1]] (empty: every string runs everywhere). span_lo, span_hi per actuator.
  std::vector<double> span_lo, span_hi;
  std::vector<std::vector<char>> string_runs;
  /// Adds the string anchors and spline routing knots to the knots, and marks the knots where
  /// the strain jumps (called by the constructor; cosserat/string_jumps.cpp).
  void add_string_knots();
  bool runs(std::size_t piece, int i) const {
    return string_runs.empty() || string_runs[piece][static_cast<std::size_t>(i)] != 0;
  }
  bool from_base(int i) const { return span_lo[static_cast<std::size_t>(i)] == 0.0; }
  bool to_tip(int i) const { return span_hi[static_cast<std::size_t>(i)] == L; }
  /// The stiffnesses, omega* and weight factor at s (one-sided limit `side` at a jump).
  void properties(double s, rod::Side side, Vec3& Kn, Vec3& Kw, Vec3& ws, double& wf) const;
  /// properties() of the model itself: omega* without the homotopy below (mu = 1).
  void model_properties(double s, rod::Side side, Vec3& Kn, Vec3& Kw, Vec3& ws, double& wf) const;
  /// The homotopy's omega* for the model's omega*(s) = ws: omega*(0) + mu (ws - omega*(0)).
  Vec3 homotopy_omega_star(const Vec3& ws) const {
    return omega_star + omega_star_fraction * (ws - omega_star);
  }

  /// Homotopy in the variation of omega* along s (the shooting solver's cold start of a body
  /// whose reference curvature varies): with fraction mu, the IVP and the tip conditions see
  ///   omega*_mu(s) = omega*(0) + mu (omega*(s) - omega*(0)),
  /// so mu = 0 is the body with the base's reference curvature throughout and mu = 1 (the
  /// default, and the value outside that start) the model, bit for bit.
  bool omega_star_varies = false;  // a component of omega* takes more than one value along s
  double omega_star_fraction = 1.0;
  Vec3 omega_star_tip_model;  // omega*(L) of the model (omega_star_tip at mu = 1)
  void set_omega_star_fraction(double mu);
};

}  // namespace tcasim::cosserat::internal
