#pragma once
/// One discretization level of the shooting IVP: the integrator of the state and, if asked,
/// of the state with its forward sensitivities, by either pose integration
/// (Options::kinematics): the flat ode::Integrator (RK4/6/8 or CVODE) or the Lie-group
/// RKMK4 (cosserat/internal/lie_rkmk4.hpp). Both report failure the same way here: integrate()
/// returns false when the integration failed or the end state is not finite.
/// Internal to the shooting solver.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "common/ode.hpp"
#include "cosserat/internal/lie_rkmk4.hpp"
#include "cosserat/shooting.hpp"

namespace tcasim::cosserat::internal {

/// A piecewise IVP (a body whose properties vary along s): the integration runs piece by
/// piece between the knots, with `steps x (piece length) / L` equal steps per piece (at
/// least one; CVODE: one integration per piece), calls `enter` before each piece and
/// applies `jump` (state) or `jump_sens` (augmented state) at each interior knot. A jump
/// returning false fails the integration.
struct PieceHooks {
  std::vector<double> knots;  ///< 0 = knots[0] < ... < knots.back() = L
  std::function<void(double lo, double hi)> enter;
  std::function<bool(std::size_t knot, Eigen::VectorXd& y)> jump;
  std::function<bool(std::size_t knot, Eigen::VectorXd& Y)> jump_sens;
};

class IntegrationLevel {
 public:
  /// dim: IVP state dimension; nx: sensitivity directions (used when `sensitivities`);
  /// options: the integrator (its `steps` are this level's; output_intervals > 0 samples the
  /// observer at that many equal intervals, 0 at every step node). Throws InputError on bad
  /// options.
  /// pieces: the piecewise IVP (nullptr: one piece [0, L]); it must outlive the level. The
  /// observer then sees every step node of every piece (each knot once, after its jump).
  IntegrationLevel(int dim, int nx, const ode::IntegratorOptions& options, Kinematics kinematics,
                   bool sensitivities, const PieceHooks* pieces = nullptr);

  /// Integrates y (size dim) from 0 to L in place; the observer sees the samples. False when
  /// the integration failed or y(L) is not finite.
  bool integrate(const ode::RhsFunction& f, double L, Eigen::VectorXd& y,
                 const ode::Observer& observer = {});
  /// Integrates the augmented state Y = (y, Y_0, ..., Y_{nx-1}) (size dim (1 + nx)) with the
  /// variational right-hand side f. Needs has_sensitivities(). False as integrate().
  bool integrate_sensitivities(const ode::RhsFunction& f, double L, Eigen::VectorXd& Y);

  /// Integrates y, the state at s0 (after any jump there), to s1 > s0, both in one piece of
  /// the piecewise IVP, with this level's method in steps no longer than its own (CVODE: its
  /// tolerances): the state at a point between sample nodes, integrated, not interpolated.
  /// Leaves the hooks in the last piece, as integrate() does. False as integrate().
  bool integrate_between(const ode::RhsFunction& f, double L, double s0, double s1,
                         Eigen::VectorXd& y);

  bool has_sensitivities() const {
    return flat_sens_.has_value() || lie_sens_.has_value() || !piece_flat_sens_.empty() ||
           !piece_lie_sens_.empty();
  }

 private:
  /// The piecewise integration of integrate() (sens: integrate_sensitivities()).
  bool integrate_pieces(const ode::RhsFunction& f, Eigen::VectorXd& y,
                        const ode::Observer& observer, bool sens);

  int dim_;
  ode::IntegratorOptions options_;
  Kinematics kinematics_;
  const PieceHooks* pieces_ = nullptr;
  std::vector<ode::Integrator> piece_flat_, piece_flat_sens_;  // one per piece
  std::vector<LieGroupRk4> piece_lie_, piece_lie_sens_;
  std::optional<ode::Integrator> flat_, flat_sens_;  // Kinematics::kFlat
  std::optional<LieGroupRk4> lie_, lie_sens_;        // Kinematics::kLieGroup
  int every_ = 1;                                    // Lie group: observe every every_-th step node
};

}  // namespace tcasim::cosserat::internal
