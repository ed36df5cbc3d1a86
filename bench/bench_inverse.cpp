// Speed of the inverse kinetostatics ([Pawlowski2019] Section IV) on a circular EcoFlex rod
// (40 mm, 8 mm) standing under gravity with two TCAs at 3 mm (0 and 90 deg), RK4.
//  - one inverse iteration with N = 2 actuators: a warm-started forward solve at a new
//    actuation (first-order predicted start) plus the tip Jacobian and compliance (Eqs.
//    (41)-(42)), by the solver's sensitivities (sens) or the literal finite-difference IVPs
//    (fd, forward differences);
//  - a full target solve from rest (both TCAs at 25 degC) to the tip position the rod
//    reaches at (70, 110) degC, to 1e-10 m.
// Argument: RK4 steps (32: tip error ~1e-8 m as in bench_cosserat; 100: the solver default).
// Run: build/bench/bench_inverse --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <vector>

#include "common/units.hpp"
#include "cosserat/inverse.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"

namespace {

using namespace tcasim;

rod::RodModel two_tca_rod() {
  rod::RodModel m = cosserat::testing::circular_rod(0.040, 0.008, 37.8e3, 0.5, 1040.0);
  m.gravity_W_m_s2 = cosserat::testing::kStandingGravity_m_s2;
  cosserat::testing::add_tca_string(m, "a", cosserat::testing::manipulator_tca(), 0.003, 0.0,
                                    units::degC_to_K(25.0));
  cosserat::testing::add_tca_string(m, "b", cosserat::testing::manipulator_tca(), 0.0, 0.003,
                                    units::degC_to_K(25.0));
  return m;
}

cosserat::Options options(int steps) {
  cosserat::Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = 1e-10;
  return o;
}

void inverse_iteration(benchmark::State& state, cosserat::TipDerivativeMethod method) {
  const rod::RodModel m = two_tca_rod();
  cosserat::ShootingSolver solver(m, options(static_cast<int>(state.range(0))));
  rod::Loads a = rod::Loads::from_model(m);
  a.set_temperature_K(0, units::degC_to_K(70.0));
  a.set_temperature_K(1, units::degC_to_K(110.0));
  cosserat::Solution sol;
  if (!solver.solve(a, sol).converged()) state.SkipWithError("initial solve failed");
  cosserat::TipDerivatives d;
  if (!cosserat::tip_derivatives(solver, m, a, sol, {0, 1}, method, d))
    state.SkipWithError("J failed");
  Eigen::VectorXd dq(2);
  double sign = 1.0;
  for (auto _ : state) {
    // Alternate +-0.5 K steps: a late inverse iteration (first-order warm start).
    dq << 0.5 * sign, -0.3 * sign;
    sign = -sign;
    for (int k = 0; k < 2; ++k) {
      a.set_temperature_K(k, a.actuators[k].segments[0].temperature_K + dq[k]);
    }
    sol.unknowns += d.du_dq * dq;
    sol.coarse_unknowns.resize(0);
    sol.jacobian = d.B_u;
    const cosserat::Summary s = solver.solve(a, sol);
    if (!s.converged()) state.SkipWithError("forward solve failed");
    state.counters["newton_iterations"] = s.iterations;
    state.counters["ivps"] = s.ivp_count;
    if (!cosserat::tip_derivatives(solver, m, a, sol, {0, 1}, method, d))
      state.SkipWithError("J failed");
    benchmark::DoNotOptimize(d.J.data());
  }
}

void BM_InverseIterationSens(benchmark::State& state) {
  inverse_iteration(state, cosserat::TipDerivativeMethod::kSensitivity);
}
void BM_InverseIterationFd(benchmark::State& state) {
  inverse_iteration(state, cosserat::TipDerivativeMethod::kForwardDifference);
}

void BM_TargetSolveFromRest(benchmark::State& state) {
  const rod::RodModel m = two_tca_rod();
  const int steps = static_cast<int>(state.range(0));
  cosserat::ShootingSolver solver(m, options(steps));
  rod::Loads goal = rod::Loads::from_model(m);
  goal.set_temperature_K(0, units::degC_to_K(70.0));
  goal.set_temperature_K(1, units::degC_to_K(110.0));
  cosserat::Solution gs;
  if (!solver.solve(goal, gs).converged()) state.SkipWithError("target solve failed");
  const Eigen::Vector3d target = gs.tip_state.head<3>();
  int iterations = 0, solves = 0;
  for (auto _ : state) {
    rod::Loads a = rod::Loads::from_model(m);  // rest: 25 degC
    cosserat::Solution sol;
    const cosserat::InverseResult r = cosserat::solve_inverse(solver, m, target, {}, a, sol);
    if (!r.converged()) state.SkipWithError("inverse did not converge");
    iterations = r.iterations;
    solves = r.forward_solves;
  }
  state.counters["iterations"] = iterations;
  state.counters["forward_solves"] = solves;
}

BENCHMARK(BM_InverseIterationSens)->Arg(32)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_InverseIterationFd)->Arg(32)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TargetSolveFromRest)->Arg(32)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
