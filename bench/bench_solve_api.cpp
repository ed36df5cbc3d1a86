// The solve of `tcasim solve` (and of tcasim.solve in Python) from a loaded scenario: the
// C++ side of the Python-overhead benchmark (bench/python_overhead.py compares the medians).
//  - cosserat: cosserat::solve(model, Options{}) of the shipped circular manipulator (RK4,
//    100 steps, the command line's defaults), returning the rod::Result;
//  - fe: beam_fe::solve + make_result with 16 quadratic elements (the defaults);
//    BM_FeMakeResult: make_result alone.
// Run: build/bench/bench_solve_api --benchmark_repetitions=10
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>

#include "beam_fe/beam_fe.hpp"
#include "cosserat/shooting.hpp"
#include "rod/result.hpp"
#include "rod/scenario.hpp"

namespace {

using namespace tcasim;

const rod::RodModel& manipulator() {
  static const rod::RodModel model = rod::read_scenario(
      std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/circular-manipulator.json");
  return model;
}

void BM_SolveCosserat(benchmark::State& state) {
  const rod::RodModel& model = manipulator();
  for (auto _ : state) {
    rod::Result r = cosserat::solve(model, cosserat::Options{});
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_SolveCosserat)->Unit(benchmark::kMicrosecond);

void BM_SolveFe(benchmark::State& state) {
  const rod::RodModel& model = manipulator();
  const beam_fe::Options options;
  for (auto _ : state) {
    beam_fe::State s;
    const beam_fe::Summary summary = beam_fe::solve(model, options, s);
    rod::Result r = beam_fe::make_result(model, options, s, summary);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_SolveFe)->Unit(benchmark::kMicrosecond);

// The result record alone (make_result of a converged state): the part of BM_SolveFe after
// the solve.
void BM_FeMakeResult(benchmark::State& state) {
  const rod::RodModel& model = manipulator();
  const beam_fe::Options options;
  beam_fe::State s;
  const beam_fe::Summary summary = beam_fe::solve(model, options, s);
  for (auto _ : state) {
    rod::Result r = beam_fe::make_result(model, options, s, summary);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_FeMakeResult)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
