#include "cosserat/integration_level.hpp"

#include "common/error.hpp"

namespace tcasim::cosserat::internal {

IntegrationLevel::IntegrationLevel(int dim, int nx, const ode::IntegratorOptions& options,
                                   Kinematics kinematics, bool sensitivities) {
  if (kinematics == Kinematics::kFlat) {
    flat_.emplace(dim, options);
    if (sensitivities) flat_sens_.emplace(dim * (1 + nx), options);
    return;
  }
  // RKMK4 takes equal steps; the same check as ode::Integrator's for fixed-step methods.
  require(options.steps >= 1, "steps", options.steps, "must be >= 1");
  lie_.emplace(dim, 0, options.steps);
  if (sensitivities) lie_sens_.emplace(dim, nx, options.steps);
  if (options.output_intervals > 0) every_ = options.steps / options.output_intervals;
}

bool IntegrationLevel::integrate(const ode::RhsFunction& f, double L, Eigen::VectorXd& y,
                                 const ode::Observer& observer) {
  if (lie_) {
    if (!observer || every_ == 1) return lie_->integrate(f, 0.0, L, y, observer) && y.allFinite();
    int node = 0;
    auto every_observer = [&](double s, const Eigen::VectorXd& yy) {
      if (node++ % every_ == 0) observer(s, yy);
    };
    return lie_->integrate(f, 0.0, L, y, every_observer) && y.allFinite();
  }
  const ode::IntegrationSummary is = flat_->integrate(f, 0.0, L, y, observer);
  return is.status == ode::IntegrationSummary::Status::kSuccess && y.allFinite();
}

bool IntegrationLevel::integrate_sensitivities(const ode::RhsFunction& f, double L,
                                               Eigen::VectorXd& Y) {
  if (lie_sens_) return lie_sens_->integrate(f, 0.0, L, Y) && Y.allFinite();
  const ode::IntegrationSummary is = flat_sens_->integrate(f, 0.0, L, Y);
  return is.status == ode::IntegrationSummary::Status::kSuccess && Y.allFinite();
}

}  // namespace tcasim::cosserat::internal
