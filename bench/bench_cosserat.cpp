// Speed of the Cosserat shooting solver (Google Benchmark).
//  - the paper's circular manipulator at 90 degC: cold solve, and one warm-started step of a
//    25..150 degC sweep (step 5 degC);
//  - a 4-tendon steel rod (tensions 15, 0, 0, 0 N, gravity along +x): cold solve.
// The manipulator benchmarks run with RK4 (lie:0) and with RKMK4 Lie-group kinematics (lie:1).
// Before the benchmarks, main() prints the tip-position error of the chosen discretization
// (and of RKMK4 at 2..32 steps) against a tight reference (RK4, 4096 steps).
// Run: build/bench/bench_cosserat --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "common/units.hpp"
#include "cosserat/models.hpp"
#include "cosserat/shooting.hpp"

namespace {

using namespace tcasim;

/// RK4 steps for the manipulator: tip error <= 1e-8 m at 90 degC (printed by main()).
constexpr int kManipulatorSteps = 32;
/// RK4 steps for the steel rod (tip error printed by main()).
constexpr int kSteelSteps = 24;

cosserat::Options options(int steps, double tolerance = 1e-10,
                          cosserat::Kinematics kin = cosserat::Kinematics::kFlat) {
  cosserat::Options o;
  o.integrator.method = ode::Method::kRk4;
  o.integrator.steps = steps;
  o.tolerance = tolerance;
  o.kinematics = kin;
  return o;
}

cosserat::Options lie_options(int steps, double tolerance = 1e-10) {
  return options(steps, tolerance, cosserat::Kinematics::kLieGroup);
}

Eigen::Vector3d tip(const rod::RodModel& m, const cosserat::Options& o) {
  cosserat::ShootingSolver solver(m, o);
  const cosserat::Actuation act = cosserat::Actuation::from_model(m);
  cosserat::Solution sol;
  const cosserat::Summary s = solver.solve(act, sol);
  if (!s.converged()) std::printf("  (not converged: %s)\n", s.message.c_str());
  std::printf("  %s steps %4d: iterations %d, IVPs %d, continuation steps %d\n", o.kinematics == cosserat::Kinematics::kLieGroup ? "RKMK4" : "RK4  ", o.integrator.steps,
              s.iterations, s.ivp_count, s.continuation_steps);
  return sol.tip_state.head<3>();
}

void print_accuracy(const char* name, const rod::RodModel& m, int steps) {
  std::printf("%s\n", name);
  const Eigen::Vector3d ref = tip(m, options(4096, 1e-10));
  const Eigen::Vector3d got = tip(m, options(steps));
  std::printf("  tip error at %d steps vs RK4 4096 steps: %.3e m\n", steps, (got - ref).norm());
  for (int n : {2, 4, 8, 16, 32}) {
    const Eigen::Vector3d lie = tip(m, lie_options(n));
    std::printf("  RKMK4 tip error at %d steps vs RK4 4096 steps: %.3e m\n", n, (lie - ref).norm());
  }
}

/// The manipulator's options: RK4 (lie = 0) or RKMK4 (lie = 1) kinematics, same step count
/// (the tip errors printed by main() are 9.5e-9 and 8.4e-9 m at 32 steps).
cosserat::Options manipulator_options(std::int64_t lie) {
  return lie ? lie_options(kManipulatorSteps) : options(kManipulatorSteps);
}

void BM_CircularManipulatorCold90degC(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(90.0));
  cosserat::ShootingSolver solver(m, manipulator_options(state.range(0)));
  const cosserat::Actuation act = cosserat::Actuation::from_model(m);
  int ivps = 0;
  for (auto _ : state) {
    cosserat::Solution sol;
    const cosserat::Summary s = solver.solve(act, sol);
    if (!s.converged()) state.SkipWithError(s.message.c_str());
    ivps = s.ivp_count;
    benchmark::DoNotOptimize(sol.unknowns.data());
  }
  state.counters["ivps"] = ivps;
}
BENCHMARK(BM_CircularManipulatorCold90degC)->Arg(0)->Arg(1)->ArgName("lie")->Unit(benchmark::kMicrosecond);

void BM_CircularManipulatorWarmSweepStep(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(25.0));
  cosserat::ShootingSolver solver(m, manipulator_options(state.range(0)));
  cosserat::Actuation act = cosserat::Actuation::from_model(m);
  cosserat::Solution start;
  solver.solve(act, start);  // the cold point at 25 degC, outside the timing
  int steps = 0;
  long ivps = 0;
  for (auto _ : state) {
    cosserat::Solution sol = start;
    for (int t = 30; t <= 150; t += 5) {
      act.set_temperature_K(0, units::degC_to_K(t));
      const cosserat::Summary s = solver.solve(act, sol);
      if (!s.converged()) state.SkipWithError(s.message.c_str());
      ++steps;
      ivps += s.ivp_count;
    }
  }
  state.counters["step_time"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ivps_per_step"] = static_cast<double>(ivps) / steps;
}
BENCHMARK(BM_CircularManipulatorWarmSweepStep)->Arg(0)->Arg(1)->ArgName("lie")->Unit(benchmark::kMicrosecond);

void BM_SteelTendonRodCold(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::steel_tendon_rod();
  cosserat::ShootingSolver solver(m, options(kSteelSteps));
  const cosserat::Actuation act = cosserat::Actuation::from_model(m);
  int ivps = 0;
  for (auto _ : state) {
    cosserat::Solution sol;
    const cosserat::Summary s = solver.solve(act, sol);
    if (!s.converged()) state.SkipWithError(s.message.c_str());
    ivps = s.ivp_count;
    benchmark::DoNotOptimize(sol.unknowns.data());
  }
  state.counters["ivps"] = ivps;
}
BENCHMARK(BM_SteelTendonRodCold)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  print_accuracy("circular manipulator, 90 degC",
                 cosserat::testing::circular_manipulator(units::degC_to_K(90.0)), kManipulatorSteps);
  print_accuracy("steel 4-tendon rod", cosserat::testing::steel_tendon_rod(), kSteelSteps);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
