// Rod dynamics benchmark: the released steel cantilever of [Till2019] (E 200 GPa, G 80 GPa,
// r 1 mm, rho 8000, L 0.5 m, 20 g tip weight released at t = 0, gravity on) at dt = 2 ms,
// alpha = -0.2, N RK4 steps along s. Counters: realtime_factor = simulated seconds per wall
// second; spatial_error_m = max |tip(N) - tip(N = 160)| over the simulated second (the same
// dt: the error of the spatial scheme alone).
// Run: build/bench/bench_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/dynamics_models.hpp"

namespace {

using namespace tcasim;
using namespace tcasim::cosserat;

constexpr double kDt = 2e-3;
constexpr int kTimeSteps = 500;  // 1 s simulated per benchmark iteration

std::vector<Eigen::Vector3d> run(int n) {
  const rod::RodModel m = testing::steel_cantilever();
  DynamicsOptions o;
  o.steps = n;
  o.dt_s = kDt;
  o.alpha = -0.2;
  RodDynamics d(m, o);
  d.initialize(testing::sag_loads(m, 0.020));
  const rod::Loads released = testing::sag_loads(m, 0.0);
  std::vector<Eigen::Vector3d> tip;
  for (int k = 0; k < kTimeSteps; ++k) {
    if (!d.step(released).converged()) break;
    tip.push_back(d.tip_position_W_m());
  }
  return tip;
}

double spatial_error(int n) {
  static const std::vector<Eigen::Vector3d> ref = run(160);
  const std::vector<Eigen::Vector3d> tip = run(n);
  if (tip.size() != ref.size()) return HUGE_VAL;
  double e = 0.0;
  for (std::size_t k = 0; k < tip.size(); ++k) e = std::max(e, (tip[k] - ref[k]).norm());
  return e;
}

void BM_ReleasedSteelCantilever(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const std::vector<Eigen::Vector3d> tip = run(n);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kTimeSteps) state.SkipWithError("a time step failed");
  }
  state.counters["realtime_factor"] =
      benchmark::Counter(kTimeSteps * kDt * state.iterations(), benchmark::Counter::kIsRate);
  static std::map<int, double> errors;
  if (!errors.count(n)) errors[n] = spatial_error(n);
  state.counters["spatial_error_m"] = errors[n];
}
BENCHMARK(BM_ReleasedSteelCantilever)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
