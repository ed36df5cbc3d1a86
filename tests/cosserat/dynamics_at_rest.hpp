#pragma once
/// The rod dynamics' static initialization against a static reference tip: on the grids of
/// N = 10, 20, 40, 80 steps (each knot a grid node) it converges at order 4, and at N = 320 to
/// within 1e-11 L (round-off at the tight tolerance).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/shooting.hpp"
#include "support/convergence.hpp"

namespace tcasim::cosserat::testing {

/// The static shooting solver with RK8 on `steps` steps at residual `tolerance` (converged to
/// round-off on these rods; its knots are piece ends, as the dynamics' grid nodes).
inline Solution static_reference(const rod::RodModel& m, const rod::Loads& loads, int steps,
                                 double tolerance) {
  Options so;
  so.integrator.method = ode::Method::kRk8;
  so.integrator.steps = steps;
  so.tolerance = tolerance;
  ShootingSolver ref(m, so);
  Solution sol;
  EXPECT_TRUE(ref.solve(loads, sol).converged());
  return sol;
}

/// Runs the ladder (printing its table under `label`) and returns the initialized N = 320
/// dynamics for further checks (nullptr if an initialization failed).
inline std::unique_ptr<RodDynamics> expect_rest_converges_at_order_four(
    const rod::RodModel& m, const rod::Loads& loads, const Eigen::Vector3d& p_ref,
    const std::vector<double>& knots, const char* label, double tolerance) {
  std::vector<double> h, err;
  for (const int n : {10, 20, 40, 80}) {
    DynamicsOptions o;
    o.steps = n;
    o.tolerance = tolerance;
    RodDynamics d(m, o);
    const std::vector<double>& s = d.grid_s_m();
    EXPECT_EQ(static_cast<int>(s.size()), d.steps() + 1);
    EXPECT_EQ(s.back(), m.length_m);
    for (const double knot : knots) {
      EXPECT_NE(std::find(s.begin(), s.end(), knot), s.end()) << "no grid node at " << knot;
    }
    const DynamicsSummary sum = d.initialize(loads);
    EXPECT_TRUE(sum.converged()) << sum.message;
    if (!sum.converged()) return nullptr;
    h.push_back(m.length_m / n);
    err.push_back((d.tip_position_W_m() - p_ref).norm());
  }
  std::printf("%s at rest:\n%s", label, test_support::convergence_table(h, err).c_str());
  test_support::ExpectOrderInBracket(h, err, 4.0, 0.5);
  DynamicsOptions o;
  o.steps = 320;
  o.tolerance = tolerance;
  auto d = std::make_unique<RodDynamics>(m, o);
  const DynamicsSummary sum = d->initialize(loads);
  EXPECT_TRUE(sum.converged()) << sum.message;
  if (!sum.converged()) return nullptr;
  EXPECT_LT((d->tip_position_W_m() - p_ref).norm(), 1e-11 * m.length_m);
  return d;
}

}  // namespace tcasim::cosserat::testing
