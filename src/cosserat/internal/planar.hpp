#pragma once
/// Planar reduction of the shooting IVP (internal to the shooting solver; docs/conventions.md
/// "Planar reduction").
///
/// A model is planar when every string is straight with its offset on the body x axis
/// (r_i = (rho_i, 0, 0)), the reference curvature is about body y only, and the gravity, tip
/// force and tip moment have no component leaving the base frame's x-z plane (gravity and
/// force: R_WB0^T v has y = 0; moment: only y). Then the rod stays in that plane: p_W(s) =
/// p_W(0) + R_WB0 (q_x, 0, q_z), R_WB = R_WB0 Rot_y(theta), nu_B = (nu_x, 0, nu_z) and
/// omega_B = (0, kappa, 0), and the 21 + n state components of the 3-D IVP reduce to 9 + n.
/// The 3-D fixed-step integration of R's nine entries keeps the structure of Rot_y exactly
/// (R' = R hat(kappa e_y) is linear in R and maps that subspace into itself), so integrating
/// (cos theta, sin theta) = (Rot_00, Rot_02) with the same scheme is the same discretization:
/// the planar and 3-D IVPs agree to round-off.
///
/// State layout (dimension kDelta + actuators), base-frame coordinates:
///   q [0,2) = (x, z) of R_WB0^T (p_W - p_W(0)); cs [2,4) = (Rot_00, Rot_02) = (cos, sin theta);
///   nu [4,6) = (nu_x, nu_z - 1) (deviation from nu* = e3, as in the 3-D layout of
///   shooting.hpp); kappa [6] = omega_y; c [7,9) = int_0^s q ds; delta_i [9, 9 + n).
#include <vector>

namespace tcasim::cosserat::planar {

inline constexpr int kQ = 0;
inline constexpr int kCS = 2;
inline constexpr int kNu = 4;
inline constexpr int kKappa = 6;
inline constexpr int kC = 7;
inline constexpr int kDelta = 9;

/// Largest number of actuators and of sensitivity directions (unknowns) of the reduction.
inline constexpr int kMaxActuators = 8;
inline constexpr int kMaxDirections = 8;

/// The planar rod: constants of the model and the parameters of the current IVP.
struct Rod {
  double kn_x = 0.0, kn_z = 0.0, kw_y = 0.0;  ///< K_nu x, z and K_omega y [N], [N m^2]
  std::vector<double> rho;                    ///< per actuator: offset along body x [m]
  std::vector<double> length_ratio;           ///< per actuator: rest length / L
  std::vector<double> count;                  ///< per actuator: parallel strings
  std::vector<int> direction_of;  ///< per actuator: sensitivity direction of its tension, or -1
  // Parameters of the current IVP.
  std::vector<double> cT;       ///< per actuator: count x tension [N]
  double f_x = 0.0, f_z = 0.0;  ///< R_WB0^T f_ext (distributed load per length) [N/m]
};

/// d y / ds of the planar IVP (docs/conventions.md "Body-frame ODEs", restricted to the plane).
void rhs(const Rod& rod, const double* y, double* dy);

/// The state and its forward sensitivities Y = (y, Y_0, ..., Y_{n_dir - 1}) (blocks of `dim`):
/// the variational equations Y_j' = (df/dy) Y_j + df/dx_j, with the tension of actuator i
/// entering direction direction_of[i] through c_i T_i. Computed by forward-mode automatic
/// differentiation of rhs() (dual numbers), so the derivative is that of the same formulas.
/// n_dir <= kMaxDirections.
void rhs_sens(const Rod& rod, int dim, int n_dir, const double* Y, double* dY);

/// Tip wrench residual (unscaled): force (x, z) in the body frame and moment about body y,
///   K_nu (nu - nu*) - R^T F_e + sum c_i T_i qh_i,  K_omega (omega - omega*) - R^T M_e + sum c_i
///   T_i r_i x qh_i
/// with F_e = R_WB0 (F_x, 0, F_z) and M_e = R_WB0 (0, M_y, 0); kappa_star = omega*_y.
void tip_wrench(const Rod& rod, double kappa_star, double F_x, double F_z, double M_y,
                const double* y, double out[3]);

/// Directional derivatives of tip_wrench along the sensitivities at the tip: column j of
/// `out` (3 x n_dir, column-major) for Y_j = dy(L)/dx_j (blocks of `dim` after y), with the
/// tensions entering as in rhs_sens.
void tip_wrench_sens(const Rod& rod, double F_x, double F_z, int dim, int n_dir, const double* Y,
                     double* out);

}  // namespace tcasim::cosserat::planar
