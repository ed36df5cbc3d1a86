// FE dynamics against the shooting dynamics (ctest label `slow`): the released steel cantilever
// of tests/cli/steel-cantilever.json (gravity along -x, the 20 g tip weight removed at t = 0),
// both methods at the same dt on fine meshes; the max tip difference over time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "beam_fe/dynamics.hpp"
#include "cosserat/dynamics.hpp"
#include "support/convergence.hpp"
#include "support/rod_models.hpp"

namespace tcasim::beam_fe {
namespace {

using test_support::sag;
rod::RodModel steel() { return test_support::steel_cantilever_till(); }

/// Tip positions after every step over `steps` steps; the solver type Dyn runs initialize/step.
template <class Dyn>
std::vector<Eigen::Vector3d> released(Dyn& d, const rod::RodModel& m, int steps, double* wall) {
  std::vector<Eigen::Vector3d> tips;
  EXPECT_TRUE(d.initialize(sag(m, 0.02)).converged());
  tips.push_back(d.tip_position_W_m());
  const rod::Loads rel = sag(m, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    const auto s = d.step(rel);
    EXPECT_TRUE(s.converged()) << s.message;
    if (!s.converged()) break;
    tips.push_back(d.tip_position_W_m());
  }
  *wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return tips;
}

TEST(BeamDynamicsSlow, ReleasedCantileverAgainstTheShootingDynamics) {
  const rod::RodModel m = steel();
  const double duration = 0.2;
  std::vector<double> h, diff;
  for (const double dt : {2e-3, 1e-3, 5e-4}) {
    const int steps = static_cast<int>(std::lround(duration / dt));
    cosserat::DynamicsOptions co;
    co.dt_s = dt;
    co.steps = 160;
    cosserat::RodDynamics cd(m, co);
    DynamicsOptions fo;
    fo.elements = 32;
    fo.dt_s = dt;
    fo.rho_inf = 0.8;
    BeamDynamics fd(m, fo);
    double wc = 0.0, wf = 0.0;
    const std::vector<Eigen::Vector3d> a = released(cd, m, steps, &wc);
    const std::vector<Eigen::Vector3d> b = released(fd, m, steps, &wf);
    ASSERT_EQ(a.size(), b.size());
    double e = 0.0, e0 = (a[0] - b[0]).norm();
    for (std::size_t k = 0; k < a.size(); ++k) e = std::max(e, (a[k] - b[k]).norm());
    std::printf(
        "dt %.1e: max_t |tip_FE - tip_shooting| = %.3e m (%.2e L), at t = 0 %.2e m; wall shooting "
        "%.2f s, FE %.2f s\n",
        dt, e, e / m.length_m, e0, wc, wf);
    h.push_back(dt);
    diff.push_back(e);
  }
  std::printf("%s", test_support::convergence_table(h, diff).c_str());
  // The two time integrators (BDF-alpha, generalized-alpha) differ at O(dt) on this release
  // (it excites modes up to hundreds of Hz): the difference must fall with dt, at about first
  // order or better.
  for (std::size_t i = 1; i < diff.size(); ++i) EXPECT_LT(diff[i], 0.7 * diff[i - 1]);
  EXPECT_LT(diff.back(), 5e-3 * m.length_m);
}

// The same release with Kelvin-Voigt damping (eta = 2e7 Pa s) in both methods: the damping law
// is the same, so the difference stays at the level of the undamped one at that dt.
TEST(BeamDynamicsSlow, DampedReleaseAgainstTheShootingDynamics) {
  const rod::RodModel m = steel();
  const double dt = 1e-3;
  const int steps = 200;
  cosserat::DynamicsOptions co;
  co.dt_s = dt;
  co.steps = 160;
  co.viscosity_Pa_s = 2e7;
  cosserat::RodDynamics cd(m, co);
  DynamicsOptions fo;
  fo.elements = 32;
  fo.dt_s = dt;
  fo.rho_inf = 0.8;
  fo.viscosity_Pa_s = 2e7;
  BeamDynamics fd(m, fo);
  double wc = 0.0, wf = 0.0;
  const std::vector<Eigen::Vector3d> a = released(cd, m, steps, &wc);
  const std::vector<Eigen::Vector3d> b = released(fd, m, steps, &wf);
  ASSERT_EQ(a.size(), b.size());
  double e = 0.0, amplitude = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    e = std::max(e, (a[k] - b[k]).norm());
    amplitude = std::max(amplitude, (a[k] - a[0]).norm());
  }
  std::printf("damped, dt %.1e: max_t |tip_FE - tip_shooting| = %.3e m (%.2e L), motion %.3e m\n",
              dt, e, e / m.length_m, amplitude);
  EXPECT_LT(e, 2e-3 * m.length_m);
  EXPECT_GT(amplitude, 10.0 * e);
}

}  // namespace
}  // namespace tcasim::beam_fe
