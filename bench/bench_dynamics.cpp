// Rod dynamics benchmarks.
// - BM_ReleasedSteelCantilever: the released steel cantilever of [Till2019] (E 200 GPa,
//   G 80 GPa, r 1 mm, rho 8000, L 0.5 m, 20 g tip weight released at t = 0, gravity on) at
//   dt = 2 ms, alpha = -0.2, N RK4 steps along s, 1 s simulated. Counters: realtime_factor =
//   simulated seconds per CPU second; s_per_step = CPU seconds per time step; iterations and
//   jacobians per time step; spatial_error_m = max |tip(N) - tip(N = 160)| over the simulated
//   second (the same dt: the error of the spatial scheme alone).
// - BM_ReleasedSteelCantileverEuler: the same with forward Euler along s (first order;
//   DynamicsOptions::SpatialScheme::kEuler), its spatial_error_m against RK4 at N = 160.
// - BM_SteelCantilever25s: the same at N = 40 over 25 s (the setting of [Till2019]'s example).
// - BM_SteelCantilever25sCoarse: the same 25 s at N RK4 steps (argument). Counters as above,
//   with spatial_error_m = max |tip(N) - tip(N = 160)| over the 25 s, and
//   euler40_spatial_error_m the same for forward Euler along s at N = 40 (a first-order spatial
//   scheme on [Till2019]'s grid; DynamicsOptions::SpatialScheme::kEuler).
// - BM_SteelCantilever25sTiming: the same 25 s at N RK4 steps (argument), timing counters only
//   (for profiles: no reference runs).
// - BM_VoltageStep10s: a voltage step (0 -> 0.714 V at t = 0+) on the paper's circular
//   manipulator (validation/scenarios/circular-manipulator-voltage.json; argument: viscosity
//   eta [Pa s], 1000 as in validate_dynamics: undamped, the rod whips and a step fails after
//   4.36 s), dt = 1 ms, the recommended grid, 10 s simulated.
// Run: build/bench/bench_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "cosserat/dynamics.hpp"
#include "cosserat/dynamics_models.hpp"
#include "rod/scenario.hpp"

namespace {

using namespace tcasim;
using namespace tcasim::cosserat;

constexpr double kDt = 2e-3;
constexpr int kTimeSteps = 500;  // 1 s simulated per benchmark iteration

/// Newton work of a run.
struct Work {
  long long steps = 0, iterations = 0, jacobians = 0;
  void add(const DynamicsSummary& s) {
    ++steps;
    iterations += s.iterations;
    jacobians += s.jacobians;
  }
};

std::vector<Eigen::Vector3d> run(
    int n, int time_steps = kTimeSteps, Work* work = nullptr,
    DynamicsOptions::SpatialScheme scheme = DynamicsOptions::SpatialScheme::kRk4) {
  const rod::RodModel m = testing::steel_cantilever();
  DynamicsOptions o;
  o.scheme = scheme;
  o.steps = n;
  o.dt_s = kDt;
  o.alpha = -0.2;
  RodDynamics d(m, o);
  d.initialize(testing::sag_loads(m, 0.020));
  const rod::Loads released = testing::sag_loads(m, 0.0);
  std::vector<Eigen::Vector3d> tip;
  for (int k = 0; k < time_steps; ++k) {
    const DynamicsSummary s = d.step(released);
    if (!s.converged()) break;
    if (work) work->add(s);
    tip.push_back(d.tip_position_W_m());
  }
  return tip;
}

/// Counters of a run of `time_steps` steps of dt [s] per benchmark iteration.
void set_counters(benchmark::State& state, const Work& w, int time_steps, double dt) {
  const double n = static_cast<double>(time_steps) * static_cast<double>(state.iterations());
  state.counters["realtime_factor"] = benchmark::Counter(n * dt, benchmark::Counter::kIsRate);
  state.counters["s_per_step"] =
      benchmark::Counter(n, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  const double steps = std::max<double>(1.0, static_cast<double>(w.steps));
  state.counters["iterations_per_step"] = static_cast<double>(w.iterations) / steps;
  state.counters["jacobians_per_step"] = static_cast<double>(w.jacobians) / steps;
}

/// max over time of |a - b| (HUGE_VAL when a run failed before the end).
double max_distance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  if (a.size() != b.size()) return HUGE_VAL;
  double e = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) e = std::max(e, (a[k] - b[k]).norm());
  return e;
}

double spatial_error(int n,
                     DynamicsOptions::SpatialScheme scheme = DynamicsOptions::SpatialScheme::kRk4) {
  static const std::vector<Eigen::Vector3d> ref = run(160);
  const std::vector<Eigen::Vector3d> tip = run(n, kTimeSteps, nullptr, scheme);
  if (tip.size() != ref.size()) return HUGE_VAL;
  double e = 0.0;
  for (std::size_t k = 0; k < tip.size(); ++k) e = std::max(e, (tip[k] - ref[k]).norm());
  return e;
}

void BM_ReleasedSteelCantilever(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Work w;
  for (auto _ : state) {
    const std::vector<Eigen::Vector3d> tip = run(n, kTimeSteps, &w);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kTimeSteps) state.SkipWithError("a time step failed");
  }
  set_counters(state, w, kTimeSteps, kDt);
  static std::map<int, double> errors;
  if (!errors.count(n)) errors[n] = spatial_error(n);
  state.counters["spatial_error_m"] = errors[n];
}
BENCHMARK(BM_ReleasedSteelCantilever)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

void BM_ReleasedSteelCantileverEuler(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Work w;
  for (auto _ : state) {
    const std::vector<Eigen::Vector3d> tip =
        run(n, kTimeSteps, &w, DynamicsOptions::SpatialScheme::kEuler);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kTimeSteps) state.SkipWithError("a time step failed");
  }
  set_counters(state, w, kTimeSteps, kDt);
  state.counters["spatial_error_m"] = spatial_error(n, DynamicsOptions::SpatialScheme::kEuler);
}
BENCHMARK(BM_ReleasedSteelCantileverEuler)
    ->Arg(40)
    ->Arg(80)
    ->Arg(160)
    ->Unit(benchmark::kMillisecond);

void BM_SteelCantilever25s(benchmark::State& state) {
  constexpr int kSteps25s = 12500;
  Work w;
  for (auto _ : state) {
    const std::vector<Eigen::Vector3d> tip = run(40, kSteps25s, &w);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kSteps25s) state.SkipWithError("a time step failed");
  }
  set_counters(state, w, kSteps25s, kDt);
}
BENCHMARK(BM_SteelCantilever25s)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_SteelCantilever25sCoarse(benchmark::State& state) {
  constexpr int kSteps25s = 12500;
  const int n = static_cast<int>(state.range(0));
  Work w;
  std::vector<Eigen::Vector3d> tip;
  for (auto _ : state) {
    tip = run(n, kSteps25s, &w);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kSteps25s) state.SkipWithError("a time step failed");
  }
  set_counters(state, w, kSteps25s, kDt);
  static const std::vector<Eigen::Vector3d> ref = run(160, kSteps25s);
  static const double euler40 =
      max_distance(run(40, kSteps25s, nullptr, DynamicsOptions::SpatialScheme::kEuler), ref);
  state.counters["spatial_error_m"] = max_distance(tip, ref);
  state.counters["euler40_spatial_error_m"] = euler40;
}
BENCHMARK(BM_SteelCantilever25sCoarse)
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

/// The 25 s of BM_SteelCantilever25s at N RK4 steps (argument) without the reference runs of
/// the error counters (a profile of it, e.g. under callgrind, holds the time steps only).
void BM_SteelCantilever25sTiming(benchmark::State& state) {
  constexpr int kSteps25s = 12500;
  const int n = static_cast<int>(state.range(0));
  Work w;
  for (auto _ : state) {
    const std::vector<Eigen::Vector3d> tip = run(n, kSteps25s, &w);
    benchmark::DoNotOptimize(tip.data());
    if (static_cast<int>(tip.size()) != kSteps25s) state.SkipWithError("a time step failed");
  }
  set_counters(state, w, kSteps25s, kDt);
}
BENCHMARK(BM_SteelCantilever25sTiming)
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

/// The circular manipulator with the voltage switched on at t = 0+ (as validate_dynamics) and
/// Kelvin-Voigt viscosity eta [Pa s] (0: none, as shipped).
rod::RodModel voltage_step_manipulator(double viscosity_Pa_s) {
  const std::string dir = std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios";
  std::ifstream in(dir + "/circular-manipulator-voltage.json");
  nlohmann::json j = nlohmann::json::parse(in);
  const double volts = j["actuators"][0]["drive"]["electric"]["voltage_V"].get<double>();
  j["actuators"][0]["drive"]["electric"] = {
      {"voltage_V", {{"step", {{"t_s", 0.0}, {"before", 0.0}, {"after", volts}}}}}};
  if (viscosity_Pa_s > 0.0) j["body"]["material"]["viscosity_Pa_s"] = viscosity_Pa_s;
  return rod::parse_scenario(j, dir);
}

void BM_VoltageStep10s(benchmark::State& state) {
  constexpr double kDtStep = 1e-3;
  constexpr int kSteps10s = 10000;
  const rod::RodModel m = voltage_step_manipulator(static_cast<double>(state.range(0)));
  DynamicsOptions o;
  o.dt_s = kDtStep;
  o.steps = recommended_steps(m, o);
  Work w;
  for (auto _ : state) {
    RodDynamics d(m, o);
    if (!d.initialize(rod::Loads::from_model(m)).converged()) {
      state.SkipWithError("the static state did not converge");
      break;
    }
    for (int k = 1; k <= kSteps10s; ++k) {
      const DynamicsSummary s = d.step(rod::Loads::at_time(m, k * kDtStep));
      if (!s.converged()) {
        state.SkipWithError(("time step " + std::to_string(k) + " failed: " + s.message).c_str());
        break;
      }
      w.add(s);
    }
    benchmark::DoNotOptimize(d.tip_position_W_m());
  }
  set_counters(state, w, kSteps10s, kDtStep);
}
BENCHMARK(BM_VoltageStep10s)->Arg(1000)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
