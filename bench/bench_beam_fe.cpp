// Speed of the beam FE solver (medians of Google Benchmark repetitions):
//  - BM_CircularManipulator64Quadratic: the paper's circular manipulator (8 mm diameter,
//    40 mm, EcoFlex E = 37.8 kPa, nu = 0.5, 1040 kg/m^3, one extension TCA at 3 mm,
//    D = 1.7 mm, alpha0 = 15 deg, N = 76.4, coiled length 40 mm, silver-nylon-sun2022)
//    at 90 degC, 64 quadratic elements, full nonlinear solve from the reference
//    configuration. Target: <= 5 ms median.
//  - BM_CircularManipulatorElements/N: the same solve for N = 16 .. 4096 quadratic
//    elements (cost vs element count; expected linear).
//  - BM_PinnedManipulator64Quadratic: the same robot with its tip pinned at
//    (-22, 1, 31) mm (tip_constraint, 3 Lagrange multipliers), 64 quadratic elements.
// Run: build-fe2/bench/bench_beam_fe --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/models.hpp"
#include "common/units.hpp"

namespace {

using namespace tcasim;

void run(benchmark::State& bench, int elements, bool pinned = false) {
  rod::RodModel model = beam_fe::testing::circular_manipulator(units::degC_to_K(90.0));
  if (pinned) {
    rod::TipConstraint c;
    c.position_W_m = {-0.022, 0.001, 0.031};
    model.tip_constraint = c;
  }
  beam_fe::Options opt;
  opt.elements = elements;
  opt.order = 2;
  beam_fe::Summary summary;
  for (auto _ : bench) {
    beam_fe::State state;
    summary = beam_fe::solve(model, opt, state);
    benchmark::DoNotOptimize(state.p_W_m.back());
  }
  if (!summary.converged()) bench.SkipWithError(summary.message.c_str());
  bench.counters["iterations"] = summary.iterations;
  bench.counters["load_steps"] = summary.load_steps;
  bench.counters["dofs"] = 6 * 2 * elements + 1 + (pinned ? 3 : 0);
}

void BM_CircularManipulator64Quadratic(benchmark::State& bench) { run(bench, 64); }
BENCHMARK(BM_CircularManipulator64Quadratic)->Unit(benchmark::kMillisecond);

void BM_CircularManipulatorElements(benchmark::State& bench) {
  run(bench, static_cast<int>(bench.range(0)));
}
BENCHMARK(BM_CircularManipulatorElements)
    ->RangeMultiplier(4)
    ->Range(16, 4096)
    ->Unit(benchmark::kMillisecond);

void BM_PinnedManipulator64Quadratic(benchmark::State& bench) { run(bench, 64, true); }
BENCHMARK(BM_PinnedManipulator64Quadratic)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
