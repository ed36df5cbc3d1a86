// Cost of a body that varies along s (docs/scenario-format.md "Profiles along the body")
// against a uniform one at the same accuracy (Google Benchmark), shooting solver, cold solves:
//  - uniform: the tapered tentacle's mean diameter (15 mm) along its whole length, straight;
//  - tapered: examples/scenarios/tapered-tentacle.json's body (diameter 20 -> 10 mm, a jump
//    of the reference curvature at L/2), the same tendons and gravity.
// Before the benchmarks, main() prints for each body the RK4 steps at which the tip error
// against a tight reference (RK4, 2048 steps) falls below kTipTolerance, and that error; the
// benchmarks run each body at its own step count (the same accuracy), each solve with the one
// solver (`cold`) or a new solver each time (`new_solver`).
// Run: build/bench/bench_varying_body --benchmark_repetitions=11
//        --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "cosserat/shooting.hpp"
#include "rod/scenario.hpp"
#include "support/varying_body.hpp"

namespace {

using namespace tcasim;

/// Tip accuracy both bodies are run at [m] (1e-7 of the 0.2 m length).
constexpr double kTipTolerance = 2e-8;

nlohmann::json tentacle(bool tapered) { return test_support::hanging_tentacle(tapered); }

cosserat::Options rk4(int steps) {
  cosserat::Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  return o;
}

int steps_for(bool tapered) {
  const rod::RodModel m = rod::parse_scenario(tentacle(tapered));
  const rod::Result ref = cosserat::solve(m, rk4(2048));
  for (int n = 4; n <= 1024; n += 2) {
    const rod::Result r = cosserat::solve(m, rk4(n));
    const double err = (r.tip_position_W_m - ref.tip_position_W_m).norm();
    if (r.converged && err <= kTipTolerance) {
      // The cost of one cold solve at these steps: Newton iterations, IVPs, continuation steps.
      cosserat::ShootingSolver solver(m, rk4(n));
      cosserat::Solution sol;
      const cosserat::Summary s = solver.solve(rod::Loads::from_model(m), sol);
      std::printf(
          "%s: %d RK4 steps, tip error %.2e m (reference 2048 steps); cold solve: %d "
          "Newton iterations, %d IVPs, %d continuation steps\n",
          tapered ? "tapered" : "uniform", n, err, s.iterations, s.ivp_count, s.continuation_steps);
      return n;
    }
  }
  return 1024;
}

void BM_ColdSolve(benchmark::State& state, bool tapered, int steps) {
  const rod::RodModel m = rod::parse_scenario(tentacle(tapered));
  cosserat::ShootingSolver solver(m, rk4(steps));
  const rod::Loads act = rod::Loads::from_model(m);
  for (auto _ : state) {
    cosserat::Solution sol;
    const cosserat::Summary s = solver.solve(act, sol);
    if (!s.converged()) state.SkipWithError("not converged");
    benchmark::DoNotOptimize(sol.unknowns.data());
  }
  state.counters["steps"] = steps;
}

/// The same cold solve with a new solver each time (what cosserat::solve does): adds the
/// solver's construction and, for the varying body, the first evaluation of its properties
/// at each grid point (RodRhs::LocalMemo), which the solves above find stored.
void BM_NewSolverColdSolve(benchmark::State& state, bool tapered, int steps) {
  const rod::RodModel m = rod::parse_scenario(tentacle(tapered));
  const rod::Loads act = rod::Loads::from_model(m);
  for (auto _ : state) {
    cosserat::ShootingSolver solver(m, rk4(steps));
    cosserat::Solution sol;
    const cosserat::Summary s = solver.solve(act, sol);
    if (!s.converged()) state.SkipWithError("not converged");
    benchmark::DoNotOptimize(sol.unknowns.data());
  }
  state.counters["steps"] = steps;
}

}  // namespace

int main(int argc, char** argv) {
  const int uniform_steps = steps_for(false);
  const int tapered_steps = steps_for(true);
  benchmark::RegisterBenchmark("uniform_tentacle/cold", BM_ColdSolve, false, uniform_steps)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("tapered_tentacle/cold", BM_ColdSolve, true, tapered_steps)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("uniform_tentacle/new_solver", BM_NewSolverColdSolve, false,
                               uniform_steps)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("tapered_tentacle/new_solver", BM_NewSolverColdSolve, true,
                               tapered_steps)
      ->Unit(benchmark::kMicrosecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
