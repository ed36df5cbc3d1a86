// The cost of contact: the finger-on-cylinder scenario of the contact suite
// (validation/scenarios/contact/tca-finger-cylinder.json, a TCA finger bent onto a peg) solved
// cold with and without its obstacle, by either method at its command-line defaults.
//  - BM_ContactSolve/<method>/<obstacle>: one cold solve per iteration (real time).
//  - BM_ContactRatio/<method>: each iteration solves without the obstacle and then with it,
//    so a change of the machine's speed hits both halves of the pair; the time is the
//    contact solve's, the counter `ratio` the pair's ratio (report the median over
//    repetitions). A solve that does not converge stops the benchmark with an error.
//  - BM_ContactSweepStep/<method>: one warm-started solve of a sweep step through contact
//    (the TCA 1 degC warmer than the previous, converged, point), iterations as a counter.
// Run: build/bench/bench_contact --benchmark_repetitions=15 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "common/units.hpp"
#include "method/method.hpp"
#include "rod/scenario.hpp"

namespace {

using namespace tcasim;

const rod::RodModel& finger(bool with_obstacle) {
  static const rod::RodModel touching = rod::read_scenario(
      std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/contact/tca-finger-cylinder.json");
  static const rod::RodModel free = [] {
    rod::RodModel m = touching;
    m.obstacles.clear();
    return m;
  }();
  return with_obstacle ? touching : free;
}

method::StaticOptions options(bool fe) {
  if (fe) return beam_fe::Options{};
  return cosserat::Options{};
}

/// One cold solve; false (with the state's error set) when it does not converge.
bool solve_once(benchmark::State& state, bool fe, bool with_obstacle, double& seconds) {
  const rod::RodModel& model = finger(with_obstacle);
  method::StaticSolver solver(model, options(fe));
  const auto t0 = std::chrono::steady_clock::now();
  const rod::Result r = solver.solve(rod::Loads::from_model(model));
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.converged) {
    state.SkipWithError(("not converged: " + r.message).c_str());
    return false;
  }
  return true;
}

void BM_ContactSolve(benchmark::State& state) {
  const bool fe = state.range(0) == 1, with_obstacle = state.range(1) == 1;
  for (auto _ : state) {
    double seconds = 0.0;
    if (!solve_once(state, fe, with_obstacle, seconds)) return;
    state.SetIterationTime(seconds);
  }
}
BENCHMARK(BM_ContactSolve)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"fe", "obstacle"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_ContactRatio(benchmark::State& state) {
  const bool fe = state.range(0) == 1;
  double ratio_sum = 0.0;
  for (auto _ : state) {
    double free_s = 0.0, contact_s = 0.0;
    if (!solve_once(state, fe, false, free_s) || !solve_once(state, fe, true, contact_s)) return;
    state.SetIterationTime(contact_s);
    ratio_sum += contact_s / free_s;
  }
  state.counters["ratio"] = ratio_sum / static_cast<double>(state.iterations());
}
BENCHMARK(BM_ContactRatio)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("fe")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_ContactSweepStep(benchmark::State& state) {
  const bool fe = state.range(0) == 1;
  const rod::RodModel& model = finger(true);
  method::StaticSolver solver(model, options(fe));
  rod::Loads loads = rod::Loads::from_model(model);
  const double t0_K = loads.actuators.at(0).segments.at(0).temperature_K;
  if (!solver.solve(loads).converged) {
    state.SkipWithError("the scenario's own point did not converge");
    return;
  }
  double iterations = 0.0;
  int step = 0;
  for (auto _ : state) {
    // Alternate 1 degC up and down: every solve is a warm start one step away.
    loads.set_temperature_K(0, t0_K + ((++step % 2) != 0 ? 1.0 : 0.0));
    const auto t0 = std::chrono::steady_clock::now();
    const rod::Result r = solver.solve(loads);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!r.converged) {
      state.SkipWithError(("not converged: " + r.message).c_str());
      return;
    }
    iterations += r.iterations;
  }
  state.counters["iterations"] = iterations / static_cast<double>(state.iterations());
}
BENCHMARK(BM_ContactSweepStep)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("fe")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
