#include "cosserat/internal/integration_level.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace tcasim::cosserat::internal {

IntegrationLevel::IntegrationLevel(int dim, int nx, const ode::IntegratorOptions& options,
                                   Kinematics kinematics, bool sensitivities,
                                   const PieceHooks* pieces)
    : dim_(dim), options_(options), kinematics_(kinematics), pieces_(pieces) {
  if (pieces_) {
    const std::vector<double>& k = pieces_->knots;
    require(k.size() >= 2, "pieces.knots", static_cast<double>(k.size()), "must have >= 2 knots");
    const double L = k.back() - k.front();
    for (std::size_t i = 0; i + 1 < k.size(); ++i) {
      const double share = (k[i + 1] - k[i]) / L;
      ode::IntegratorOptions o = options;
      // Steps (and CVODE output intervals) in proportion to the piece length, at least one.
      o.steps = std::max(1, static_cast<int>(std::lround(options.steps * share)));
      o.output_intervals =
          options.output_intervals > 0 && options.method == ode::Method::kCvode
              ? std::max(1, static_cast<int>(std::lround(options.output_intervals * share)))
              : 0;
      if (kinematics == Kinematics::kFlat) {
        piece_flat_.emplace_back(dim, o);
        if (sensitivities) piece_flat_sens_.emplace_back(dim * (1 + nx), o);
      } else {
        require(o.steps >= 1, "steps", o.steps, "must be >= 1");
        piece_lie_.emplace_back(dim, 0, o.steps);
        if (sensitivities) piece_lie_sens_.emplace_back(dim, nx, o.steps);
      }
    }
    return;
  }
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

bool IntegrationLevel::integrate_pieces(const ode::RhsFunction& f, Eigen::VectorXd& y,
                                        const ode::Observer& observer, bool sens) {
  const std::vector<double>& k = pieces_->knots;
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    pieces_->enter(k[i], k[i + 1]);
    if (i > 0 && !(sens ? pieces_->jump_sens(i, y) : pieces_->jump(i, y))) return false;
    // Each knot is observed once: the start of a later piece is the end of the one before
    // (after the jump: the strains on the right of the knot).
    ode::Observer piece_observer;
    if (observer) {
      piece_observer = [&](double s, const Eigen::VectorXd& yy) {
        if (i == 0 || s != k[i]) observer(s, yy);
      };
      if (i > 0) observer(k[i], y);
    }
    if (!piece_lie_.empty()) {
      LieGroupRk4& lie = sens ? piece_lie_sens_[i] : piece_lie_[i];
      if (!lie.integrate(f, k[i], k[i + 1], y, piece_observer) || !y.allFinite()) return false;
    } else {
      ode::Integrator& in = sens ? piece_flat_sens_[i] : piece_flat_[i];
      const ode::IntegrationSummary is = in.integrate(f, k[i], k[i + 1], y, piece_observer);
      if (is.status != ode::IntegrationSummary::Status::kSuccess || !y.allFinite()) return false;
    }
  }
  return true;
}

bool IntegrationLevel::integrate(const ode::RhsFunction& f, double L, Eigen::VectorXd& y,
                                 const ode::Observer& observer) {
  if (pieces_) return integrate_pieces(f, y, observer, false);
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

bool IntegrationLevel::integrate_between(const ode::RhsFunction& f, double L, double s0, double s1,
                                         Eigen::VectorXd& y) {
  // The step length h of the level where [s0, s1] lies: steps x (piece length) / L per piece.
  double h = L / std::max(1, options_.steps);
  if (pieces_) {
    const std::vector<double>& k = pieces_->knots;
    std::size_t i = 0;
    while (i + 2 < k.size() && k[i + 1] <= s0) ++i;
    const double share = (k[i + 1] - k[i]) / (k.back() - k.front());
    h = (k[i + 1] - k[i]) / std::max(1, static_cast<int>(std::lround(options_.steps * share)));
    pieces_->enter(k[i], k[i + 1]);
  }
  // Steps of at most h (the relative slack keeps a span of exactly h in one step).
  const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / h * (1.0 - 1e-12))));
  bool ok = false;
  if (kinematics_ == Kinematics::kLieGroup) {
    LieGroupRk4 lie(dim_, 0, n);
    ok = lie.integrate(f, s0, s1, y) && y.allFinite();
  } else {
    ode::IntegratorOptions o = options_;
    if (ode::is_fixed_step(o.method)) o.steps = n;
    o.output_intervals = 0;
    ode::Integrator in(dim_, o);
    ok = in.integrate(f, s0, s1, y).status == ode::IntegrationSummary::Status::kSuccess &&
         y.allFinite();
  }
  if (pieces_) {
    const std::vector<double>& k = pieces_->knots;
    pieces_->enter(k[k.size() - 2], k.back());
  }
  return ok;
}

bool IntegrationLevel::integrate_sensitivities(const ode::RhsFunction& f, double L,
                                               Eigen::VectorXd& Y) {
  if (pieces_) return integrate_pieces(f, Y, {}, true);
  if (lie_sens_) return lie_sens_->integrate(f, 0.0, L, Y) && Y.allFinite();
  const ode::IntegrationSummary is = flat_sens_->integrate(f, 0.0, L, Y);
  return is.status == ode::IntegrationSummary::Status::kSuccess && Y.allFinite();
}

}  // namespace tcasim::cosserat::internal
