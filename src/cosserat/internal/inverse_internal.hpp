#pragma once
// Internal to src/cosserat: the helpers the inverse solvers share (inverse.cpp defines them;
// inverse_jacobian.cpp, inverse_target.cpp and inverse.cpp's grasp solver use them).
#include <Eigen/Core>
#include <optional>

#include "cosserat/inverse.hpp"

namespace tcasim::cosserat::inverse_internal {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Whether actuator i is a TCA drive.
bool is_tca(const rod::RodModel& m, int i);

/// Index of actuator i's tension in the shooting unknowns (-1 for a tension drive).
int unknown_index(const rod::RodModel& m, int i);

/// The inverse and grasp solvers adjust one temperature per TCA: a segmented drive (one
/// temperature per segment) is refused rather than silently made uniform.
void require_uniform_temperature(const rod::RodModel& m, int i);

/// The adjusted variable of actuator i: its temperature [K] (TCA) or tension [N].
double get_variable(const rod::RodModel& m, const rod::Loads& a, int i);

/// Sets the adjusted variable of actuator i (see get_variable).
void set_variable(const rod::RodModel& m, rod::Loads& a, int i, double v);

/// R of a shooting state y.
Mat3 rotation_of(const Eigen::VectorXd& y);

/// vee of the skew part of M (a rotation increment dR R^T).
Vec3 skew_vee(const Mat3& M);

/// Tip pose difference (y_a - y_b) as (dp_W, vee(skew((R_a - R_b) R0^T))).
Eigen::Matrix<double, 6, 1> pose_difference(const Eigen::VectorXd& ya, const Eigen::VectorXd& yb,
                                            const Mat3& R0);

/// d phi / dT of actuator i's TCA row (tca::contact_residual, the TCA law with coil contact)
/// at tension T and elongation delta for a uniform shift of its segment temperatures [N/K]:
/// -dF/dT while the coils are open, 0 while they are closed.
double tca_dphi_dT(const rod::RodModel& m, const rod::Loads& a, int i, double tension_N,
                   double delta_m);

/// A TCA whose coils are all closed in the solved state (tension x[u]) carries whatever
/// strut force equilibrium needs: the rod does not change with its temperature up to the
/// onset, where the coils open under that force (Tca::onset_temperature). Returns the
/// temperature just above that onset (the same state, now with a temperature sensitivity) if
/// it lies below t_hi_K; none for an open TCA, a tension drive or an onset out of range.
std::optional<double> opening_temperature(const rod::RodModel& m, const rod::Loads& a, int i,
                                          const Solution& solution, double t_hi_K);

/// Scale of actuator i's variable v for steps and trust regions: max(|v|, 300 K) or max(|v|, F_c).
double variable_scale(const rod::RodModel& m, int i, double v, double Fc);

}  // namespace tcasim::cosserat::inverse_internal
