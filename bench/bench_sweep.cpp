// The parallel sweep inside the library, without the process around it: study::solve_chunks
// of the 1000-point temperature sweep of bench/sweep_jobs.py (the shipped circular
// manipulator's TCA, 25 to 150 degC, chunks of study::kDefaultSweepChunk points, the command
// line's default options of either method) on 1 and on 2 threads.
//  - BM_Sweep/<method>/<jobs>: one whole sweep per iteration (real time).
//  - BM_SweepSpeedup/<method>: each iteration runs the sweep on 1 thread and then on 2, so a
//    change of the machine's speed hits both halves of the pair; the time is the 2-thread
//    run's, the counter `speedup` the pair's ratio (the median over repetitions is the
//    number to report). Every 2-thread sweep is checked against the 1-thread one (the tips,
//    bit for bit); a difference stops the benchmark with an error.
// `bench/sweep_jobs.py` measures the same sweep through `tcasim sweep`, start-up, reading and
// writing included.
// Run: build/bench/bench_sweep --benchmark_repetitions=15 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "common/parallel.hpp"
#include "common/units.hpp"
#include "rod/scenario.hpp"
#include "study/sweep.hpp"

namespace {

using namespace tcasim;

constexpr std::size_t kPoints = 1000;

const rod::RodModel& manipulator() {
  static const rod::RodModel model = rod::read_scenario(
      std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/circular-manipulator.json");
  return model;
}

study::Sweep make_sweep(bool fe) {
  const rod::RodModel& model = manipulator();
  study::Sweep sweep;
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    if (model.actuators[i].name == "tca") sweep.actuator = i;
  }
  sweep.by_temperature = true;
  for (std::size_t k = 0; k < kPoints; ++k) {
    const double degC = 25.0 + (150.0 - 25.0) * static_cast<double>(k) / (kPoints - 1);
    sweep.values.push_back(units::degC_to_K(degC));
  }
  if (fe) {
    sweep.method = beam_fe::Options{};
  } else {
    sweep.method = cosserat::Options{};
  }
  return sweep;
}

/// Runs the sweep on `jobs` threads; returns the tip positions in sweep order.
std::vector<Eigen::Vector3d> run(const study::Sweep& sweep, int jobs) {
  const std::vector<IndexRange> chunks =
      fixed_chunks(sweep.values.size(), static_cast<std::size_t>(study::kDefaultSweepChunk));
  std::vector<Eigen::Vector3d> tips(sweep.values.size());
  study::solve_chunks(manipulator(), sweep, chunks, IndexRange{0, chunks.size()}, jobs,
                      [&](std::size_t k, rod::Result&& r) { tips[k] = r.tip_position_W_m; });
  return tips;
}

void BM_Sweep(benchmark::State& state) {
  const study::Sweep sweep = make_sweep(state.range(0) == 1);
  const int jobs = static_cast<int>(state.range(1));
  for (auto _ : state) {
    std::vector<Eigen::Vector3d> tips = run(sweep, jobs);
    benchmark::DoNotOptimize(tips);
  }
}
BENCHMARK(BM_Sweep)
    ->ArgNames({"fe", "jobs"})
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_SweepSpeedup(benchmark::State& state) {
  const study::Sweep sweep = make_sweep(state.range(0) == 1);
  using Clock = std::chrono::steady_clock;
  double serial_s = 0.0;
  double parallel_s = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const std::vector<Eigen::Vector3d> one = run(sweep, 1);
    const auto t1 = Clock::now();
    const std::vector<Eigen::Vector3d> two = run(sweep, 2);
    const auto t2 = Clock::now();
    serial_s += std::chrono::duration<double>(t1 - t0).count();
    parallel_s += std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(std::chrono::duration<double>(t2 - t1).count());
    if (one != two) {
      state.SkipWithError("the 2-thread sweep differs from the 1-thread sweep");
      break;
    }
  }
  if (parallel_s > 0.0) state.counters["speedup"] = serial_s / parallel_s;
}
BENCHMARK(BM_SweepSpeedup)
    ->ArgName("fe")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

}  // namespace

BENCHMARK_MAIN();
