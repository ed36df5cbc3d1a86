#pragma once
/// The reference (unloaded) path of a string: its length, which is the string's rest
/// length, and its regularity (docs/scenario-format.md, "Rest length and regularity").
///
/// In the reference configuration nu = e3 and omega = omega* (constant, body frame), so the
/// string's tangent is [Pawlowski2019] Eq. (19) at rest:
///   q*(s) = e3 + omega* x r(s) + r'(s),   length = int_0^L |q*(s)| ds.
/// Its axial component e3 . q* = 1 + omega*_1 r_y - omega*_2 r_x says whether the string
/// advances along the body; where it is <= 0 the string path folds back (the offset lies
/// at or beyond the centre of curvature of the precurved body).
#include <Eigen/Core>

#include "rod/model.hpp"

namespace tcasim::rod {

/// Length and regularity of one string's reference path.
struct ReferencePath {
  double length_m = 0.0;       ///< int_0^L |q*(s)| ds
  double min_axial = 1.0;      ///< min over s in [0, L] of e3 . q*(s) (dimensionless)
  double min_axial_s_m = 0.0;  ///< an s where the minimum is attained [m]
};

/// The reference path of `routing` on a body of length `length_m` [m] with constant
/// reference curvature `omega_B_1_m` (omega*, body frame) [1/m]. Straight string: closed
/// form L |q*|. Helix: |q*| depends on s only through the phase t = phi + 2 pi k s, so the
/// integral is (whole periods) x (one period) + (the remainder), each by composite
/// Gauss-Legendre quadrature refined until it changes by round-off only.
ReferencePath reference_path(const Routing& routing, const Eigen::Vector3d& omega_B_1_m,
                             double length_m);
/// The same over the span [s0, s1] (a string anchored inside the body): int_s0^s1 |q*| ds.
ReferencePath reference_path(const Routing& routing, const Eigen::Vector3d& omega_B_1_m,
                             double s0_m, double s1_m);

/// The reference path of `routing` on `model`'s body, whose omega* may vary along s
/// (docs/scenario-format.md "Profiles along the body"): the constant-curvature function above
/// when omega* is constant; else, on each piece between the breakpoints of omega*'s profiles,
/// composite Gauss-Legendre quadrature refined to round-off, and the minimum of e3 . q* at
/// the piece ends (exact for a straight string: it is linear in s there) and, for a helix, at
/// 256 points per piece. A spline routing always takes this piecewise path, its knots being
/// piece ends too (each piece evaluated on its own side of a kink).
ReferencePath reference_path(const Routing& routing, const RodModel& model);
/// The same over the span [s0, s1] of an anchored string.
ReferencePath reference_path(const Routing& routing, const RodModel& model, double s0_m,
                             double s1_m);

}  // namespace tcasim::rod
