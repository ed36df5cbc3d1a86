// Resolved rod-dynamics checks (ctest label `slow`; the quick versions are in
// dynamics_checks_test.cpp): the first three bending frequencies of the slender cantilever with
// and without a tip mass against Euler-Bernoulli to 1e-4, the dt order of the frequency error,
// and second order in dt of the trajectory under a smooth tip-force pulse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dynamics_models.hpp"
#include "support/convergence.hpp"
#include "validation/dynamics/dynamics_checks.hpp"

namespace tcasim::cosserat::testing {
namespace {

namespace dc = tcasim::dynamics_checks;

rod::RodModel slender_rod() { return steel_cantilever(0.5e-3, 0.5); }

DynamicsOptions options_at(const rod::RodModel& m, double dt, double mt = 0.0) {
  DynamicsOptions o;
  o.dt_s = dt;
  o.alpha = -0.2;
  o.tolerance = 1e-12;
  o.tip_mass_kg = mt;
  o.steps = recommended_steps(m, o);
  return o;
}

/// Released from a static tip deflection of 1e-4 L (amplitude effects ~1e-8), one period of
/// mode 1, the first three modes (and mode 4 to absorb its leak) fitted jointly.
dc::FreeVibration three_modes(double dt, double mt) {
  const rod::RodModel m = slender_rod();
  const dc::Beam b = dc::beam_of(m, mt);
  const double w1 = dc::eb_frequencies_rad_s(b, 1)[0];
  const int every = std::max(1, static_cast<int>(std::lround(2.5e-5 / dt * 4.0)));
  return dc::free_vibration(m, options_at(m, dt, mt), 1e-4 * 3.0 * b.EI / (b.L * b.L),
                            2.0 * dc::kPi / w1, 3, every);
}

void print(const char* what, double dt, const dc::FreeVibration& fv) {
  for (int k = 0; k < 3; ++k)
    std::printf(
        "%s dt %.2e N %d: mode %d omega %.8f EB %.8f (%+.2e) Timoshenko %.8f (%+.2e) "
        "Timoshenko + scheme (%+.2e)\n",
        what, dt, fv.grid_steps, k + 1, fv.omega[k], fv.omega_eb[k], fv.eb_error(k),
        fv.omega_timo[k], fv.timo_error(k), fv.omega[k] / fv.omega_sched[k] - 1.0);
  std::printf("  %d steps, %.1f s wall\n", fv.steps, fv.wall_s);
}

// At dt = 2.5e-5 s (omega_3 dt = 7.7e-3, BDF-alpha period error 1.4e-5 on mode 3) the first three
// frequencies lie within 1e-4 of Euler-Bernoulli (measured -2.1e-6, -1.6e-5, -4.7e-5 without
// tip mass; the Timoshenko corrections are -2e-6, -1.4e-5, -3.4e-5 of it), and within 1e-6 of
// the Timoshenko frequencies shifted by the scheme's oscillator error. Tip mass: mu = 0.5.
TEST(DynamicsChecksSlow, FirstThreeFrequenciesMatchEulerBernoulliWithAndWithoutTipMass) {
  const dc::Beam b = dc::beam_of(slender_rod(), 0.0);
  for (const double mu : {0.0, 0.5}) {
    SCOPED_TRACE(mu);
    const dc::FreeVibration fv = three_modes(2.5e-5, mu * b.rhoA * b.L);
    ASSERT_TRUE(fv.converged) << fv.message;
    print(mu > 0.0 ? "mu 0.5" : "mu 0", 2.5e-5, fv);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(std::abs(fv.eb_error(k)), 1e-4) << "mode " << k + 1;
      EXPECT_LT(std::abs(fv.omega[k] / fv.omega_sched[k] - 1.0), 1e-6) << "mode " << k + 1;
    }
  }
}

// The frequency error against Timoshenko falls at second order in dt (the BDF-alpha period
// error): dt = 1e-4, 5e-5, 2.5e-5.
TEST(DynamicsChecksSlow, FrequencyErrorIsSecondOrderInDt) {
  std::vector<double> h;
  std::vector<std::vector<double>> err(3);
  for (const double dt : {1e-4, 5e-5, 2.5e-5}) {
    const dc::FreeVibration fv = three_modes(dt, 0.0);
    ASSERT_TRUE(fv.converged) << fv.message;
    print("mu 0", dt, fv);
    h.push_back(dt);
    for (int k = 0; k < 3; ++k) err[k].push_back(std::abs(fv.timo_error(k)));
  }
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k + 1);
    std::printf("mode %d\n%s", k + 1, test_support::convergence_table(h, err[k]).c_str());
    test_support::ExpectOrderInBracket(h, err[k], 2.0, 0.2);
  }
}

// Under smooth forcing (a sin^2 tip-force pulse of 0.2 s, then free motion to 0.9 s, no
// damping) the tip trajectory converges at second order in dt; reference dt = 6.25e-5 s. The
// sudden release converges more slowly (about first order: dynamics_slow_test.cpp
// ReleasedCantileverDtLadder), as it excites every bending mode.
TEST(DynamicsChecksSlow, SmoothlyForcedTrajectoryIsSecondOrderInDt) {
  const rod::RodModel m = slender_rod();
  const dc::Beam b = dc::beam_of(m, 0.0);
  const double F0 = 1e-2 * 3.0 * b.EI / (b.L * b.L);
  auto run = [&](double dt) {
    const int every = static_cast<int>(std::lround(0.01 / dt));
    return dc::forced_run(
        m, options_at(m, dt), [F0](double t) { return dc::sine_squared_pulse(t, F0, 0.2); }, 0.9,
        every);
  };
  const dc::ForcedRun ref = run(6.25e-5);
  ASSERT_TRUE(ref.converged) << ref.message;
  std::vector<double> h, err;
  for (const double dt : {2e-3, 1e-3, 5e-4, 2.5e-4}) {
    const dc::ForcedRun r = run(dt);
    ASSERT_TRUE(r.converged) << r.message;
    ASSERT_EQ(r.tip_x.size(), ref.tip_x.size());
    double e = 0.0;
    for (std::size_t i = 0; i < r.tip_x.size(); ++i)
      e = std::max(e, std::abs(r.tip_x[i] - ref.tip_x[i]));
    h.push_back(dt);
    err.push_back(e / m.length_m);
  }
  std::printf("%s", test_support::convergence_table(h, err).c_str());
  test_support::ExpectOrderInBracket(h, err, 2.0, 0.2);
}

}  // namespace
}  // namespace tcasim::cosserat::testing
