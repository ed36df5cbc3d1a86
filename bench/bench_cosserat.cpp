// Speed of the Cosserat shooting solver (Google Benchmark).
//  - the paper's circular manipulator at 90 degC: cold solve; the warm-started step from
//    85 to 90 degC of a 5 degC sweep; the mean warm-started step of a 25..150 degC sweep;
//  - a 4-tendon steel rod (tensions 15, 0, 0, 0 N, gravity along +x): cold solve; a warm
//    start from its converged unknowns perturbed by 1e-3 (relative) against the cold solve
//    with the same options (RK4 100 steps, RK8 2 steps).
// The manipulator benchmarks run with RK4 at 32 steps (scheme:4, lie:0), RKMK4 Lie-group
// kinematics at 32 steps (scheme:4, lie:1), RK6 at 10 steps (scheme:6) and RK8 at 4 steps
// (scheme:8, coarse level 2 steps), each at the default tolerance 1e-10 (tol:10) and at
// 1e-8 (tol:8, for RK6), in the plane (planar:1, Options::planar_reduction, the default) and,
// for comparison, as a 3-D problem (planar:0; the results agree to round-off). The steel rod
// (tendons off the bending plane: a 3-D problem) runs with RK4 at 24 steps and RK8 at 2 steps.
// Before the benchmarks, main() prints the tip-position error of each discretization (and
// of RKMK4 at 2..32 steps) against a tight reference (RK4, 4096 steps), at 90 degC and the
// largest over the sweep, including the error of stopping at the tolerance.
// Run: build/bench/bench_cosserat --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
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
/// RK6 steps for the manipulator (tip error printed by main()).
constexpr int kManipulatorRk6Steps = 10;
/// RK6's coarse level (Options::coarse_steps): its sensitivity Jacobians start each warm step.
constexpr int kManipulatorRk6CoarseSteps = 4;
/// RK8 steps for the manipulator (tip error printed by main()) and its coarse level.
constexpr int kManipulatorRk8Steps = 4;
constexpr int kManipulatorRk8CoarseSteps = 2;
/// RK4 steps for the steel rod (tip error printed by main()).
constexpr int kSteelSteps = 24;
/// RK8 steps for the steel rod (tip error printed by main()).
constexpr int kSteelRk8Steps = 2;

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

cosserat::Options rk6_options(double tolerance) {
  cosserat::Options o = options(kManipulatorRk6Steps, tolerance);
  o.integrator.method = ode::Method::kRk6;
  o.coarse_steps = kManipulatorRk6CoarseSteps;
  return o;
}

cosserat::Options rk8_options(double tolerance) {
  cosserat::Options o = options(kManipulatorRk8Steps, tolerance);
  o.integrator.method = ode::Method::kRk8;
  o.coarse_steps = kManipulatorRk8CoarseSteps;
  return o;
}

Eigen::Vector3d tip(const rod::RodModel& m, const cosserat::Options& o) {
  cosserat::ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  cosserat::Solution sol;
  const cosserat::Summary s = solver.solve(act, sol);
  if (!s.converged()) std::printf("  (not converged: %s)\n", s.message.c_str());
  std::printf("  %s steps %4d: iterations %d, IVPs %d, continuation steps %d\n",
              o.kinematics == cosserat::Kinematics::kLieGroup ? "RKMK4"
                                                              : ode::to_string(o.integrator.method),
              o.integrator.steps, s.iterations, s.ivp_count, s.continuation_steps);
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

/// The manipulator's options for the benchmark arguments (scheme 4, 6 or 8, lie 0 or 1,
/// tolerance 10^-tol, planar 0 or 1: Options::planar_reduction; the manipulator is planar, so
/// planar:1 solves in the plane except with lie:1, which the reduction does not cover).
cosserat::Options manipulator_options(std::int64_t scheme, std::int64_t lie, std::int64_t tol,
                                      std::int64_t planar) {
  const double tolerance = std::pow(10.0, -static_cast<double>(tol));
  cosserat::Options o;
  if (scheme == 6) {
    o = rk6_options(tolerance);
  } else if (scheme == 8) {
    o = rk8_options(tolerance);
  } else {
    o = lie ? lie_options(kManipulatorSteps, tolerance) : options(kManipulatorSteps, tolerance);
  }
  o.planar_reduction = planar != 0;
  return o;
}

cosserat::Options manipulator_options(const benchmark::State& state) {
  return manipulator_options(state.range(0), state.range(1), state.range(2), state.range(3));
}

void manipulator_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"scheme", "lie", "tol", "planar"});
  b->Args({4, 0, 10, 1})->Args({4, 1, 10, 0})->Args({6, 0, 10, 1})->Args({6, 0, 8, 1});
  b->Args({8, 0, 10, 1})->Args({4, 0, 10, 0})->Args({6, 0, 10, 0})->Args({8, 0, 10, 0});
  b->Unit(benchmark::kMicrosecond);
}

/// Times solve(act) from a copy of `start` (an empty Solution: a cold solve; the copy is
/// inside the timing, about 0.3 us with a path); reports the IVP count of one solve.
void time_solves(benchmark::State& state, cosserat::ShootingSolver& solver, const rod::Loads& act,
                 const cosserat::Solution& start) {
  int ivps = 0;
  for (auto _ : state) {
    cosserat::Solution sol = start;
    const cosserat::Summary s = solver.solve(act, sol);
    if (!s.converged()) state.SkipWithError(s.message.c_str());
    ivps = s.ivp_count;
    benchmark::DoNotOptimize(sol.unknowns.data());
  }
  state.counters["ivps"] = ivps;
}

void BM_CircularManipulatorCold90degC(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(90.0));
  cosserat::ShootingSolver solver(m, manipulator_options(state));
  const rod::Loads act = rod::Loads::from_model(m);
  time_solves(state, solver, act, cosserat::Solution());
}
BENCHMARK(BM_CircularManipulatorCold90degC)->Apply(manipulator_args);

/// Sweeps 25 degC (cold) to last_degC in 5 degC warm steps; returns the last solution.
cosserat::Solution sweep_to(cosserat::ShootingSolver& solver, rod::Loads& act, int last_degC) {
  cosserat::Solution sol;
  for (int t = 25; t <= last_degC; t += 5) {
    act.set_temperature_K(0, units::degC_to_K(t));
    solver.solve(act, sol);
  }
  return sol;
}

/// One warm step, 85 -> 90 degC, from the sweep's solution at 85 degC (with its path).
void BM_CircularManipulatorWarmStepTo90degC(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(25.0));
  cosserat::ShootingSolver solver(m, manipulator_options(state));
  rod::Loads act = rod::Loads::from_model(m);
  const cosserat::Solution at85 = sweep_to(solver, act, 85);
  act.set_temperature_K(0, units::degC_to_K(90.0));
  time_solves(state, solver, act, at85);
}
BENCHMARK(BM_CircularManipulatorWarmStepTo90degC)->Apply(manipulator_args);

/// The mean warm step of the 30..150 degC sweep (25 steps) from the cold point at 25 degC.
void BM_CircularManipulatorWarmSweepStep(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(25.0));
  cosserat::ShootingSolver solver(m, manipulator_options(state));
  rod::Loads act = rod::Loads::from_model(m);
  const cosserat::Solution start = sweep_to(solver, act, 25);  // outside the timing
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
  state.counters["step_time"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["ivps_per_step"] = static_cast<double>(ivps) / steps;
}
BENCHMARK(BM_CircularManipulatorWarmSweepStep)->Apply(manipulator_args);

void BM_SteelTendonRodCold(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::steel_tendon_rod();
  cosserat::ShootingSolver solver(m, options(kSteelSteps));
  const rod::Loads act = rod::Loads::from_model(m);
  time_solves(state, solver, act, cosserat::Solution());
}
BENCHMARK(BM_SteelTendonRodCold)->Unit(benchmark::kMicrosecond);

void BM_SteelTendonRodColdRk8(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::steel_tendon_rod();
  cosserat::Options o = options(kSteelRk8Steps);
  o.integrator.method = ode::Method::kRk8;
  cosserat::ShootingSolver solver(m, o);
  const rod::Loads act = rod::Loads::from_model(m);
  time_solves(state, solver, act, cosserat::Solution());
}
BENCHMARK(BM_SteelTendonRodColdRk8)->Unit(benchmark::kMicrosecond);

/// Steel rod options for the warm-versus-cold benchmarks: scheme 4 (RK4, `steps` steps) or 8
/// (RK8).
cosserat::Options steel_options(const benchmark::State& state) {
  cosserat::Options o = options(static_cast<int>(state.range(1)));
  if (state.range(0) == 8) o.integrator.method = ode::Method::kRk8;
  return o;
}

void steel_warm_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"scheme", "steps"});
  b->Args({4, 100})->Args({8, 2});
  b->Unit(benchmark::kMicrosecond);
}

/// Relative perturbation of the converged unknowns a warm start begins from.
constexpr double kSteelWarmPerturbation = 1e-3;

/// A warm start on the steel rod from its converged unknowns scaled by 1 + 1e-3 (with that
/// solution's Jacobian and coarse-level fields, no path): compare with
/// BM_SteelTendonRodColdSameOptions; a warm start should not cost more than a cold one.
void BM_SteelTendonRodWarmPerturbed(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::steel_tendon_rod();
  cosserat::ShootingSolver solver(m, steel_options(state));
  const rod::Loads act = rod::Loads::from_model(m);
  cosserat::Solution start;
  if (!solver.solve(act, start).converged()) state.SkipWithError("cold solve failed");
  start.unknowns *= 1.0 + kSteelWarmPerturbation;
  start.path.clear();
  time_solves(state, solver, act, start);
}
BENCHMARK(BM_SteelTendonRodWarmPerturbed)->Apply(steel_warm_args);

/// The cold solve with the options of BM_SteelTendonRodWarmPerturbed.
void BM_SteelTendonRodColdSameOptions(benchmark::State& state) {
  const rod::RodModel m = cosserat::testing::steel_tendon_rod();
  cosserat::ShootingSolver solver(m, steel_options(state));
  const rod::Loads act = rod::Loads::from_model(m);
  time_solves(state, solver, act, cosserat::Solution());
}
BENCHMARK(BM_SteelTendonRodColdSameOptions)->Apply(steel_warm_args);

/// Largest tip error of a warm-started 25..150 degC sweep with `o` against RK4 at 4096 steps.
void print_sweep_accuracy(const char* name, const cosserat::Options& o) {
  const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(25.0));
  cosserat::ShootingSolver solver(m, o), reference(m, options(4096, 1e-12));
  rod::Loads act = rod::Loads::from_model(m);
  cosserat::Solution sol, ref;
  double worst = 0.0, at90 = 0.0;
  int worst_degC = 25;
  for (int t = 25; t <= 150; t += 5) {
    act.set_temperature_K(0, units::degC_to_K(t));
    const cosserat::Summary s = solver.solve(act, sol);
    const cosserat::Summary r = reference.solve(act, ref);
    if (!s.converged() || !r.converged()) std::printf("  (not converged at %d degC)\n", t);
    const double e = (sol.tip_state.head<3>() - ref.tip_state.head<3>()).norm();
    if (e > worst) {
      worst = e;
      worst_degC = t;
    }
    if (t == 90) at90 = e;
  }
  std::printf("  %-26s sweep tip error: %.2e m at 90 degC, largest %.2e m at %d degC\n", name, at90,
              worst, worst_degC);
}

}  // namespace

int main(int argc, char** argv) {
  print_accuracy("circular manipulator, 90 degC",
                 cosserat::testing::circular_manipulator(units::degC_to_K(90.0)),
                 kManipulatorSteps);
  std::printf("circular manipulator, RK6 at %d steps, 90 degC\n", kManipulatorRk6Steps);
  {
    const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(90.0));
    const Eigen::Vector3d ref = tip(m, options(4096, 1e-12));
    for (double tol : {1e-10, 1e-8}) {
      std::printf("  tip error at tolerance %.0e vs RK4 4096 steps: %.3e m\n", tol,
                  (tip(m, rk6_options(tol)) - ref).norm());
    }
  }
  std::printf("circular manipulator, RK8 at %d steps, 90 degC\n", kManipulatorRk8Steps);
  {
    const rod::RodModel m = cosserat::testing::circular_manipulator(units::degC_to_K(90.0));
    const Eigen::Vector3d ref = tip(m, options(4096, 1e-12));
    std::printf("  tip error at tolerance 1e-10 vs RK4 4096 steps: %.3e m\n",
                (tip(m, rk8_options(1e-10)) - ref).norm());
  }
  std::printf("circular manipulator, warm-started sweeps 25..150 degC (5 degC steps)\n");
  print_sweep_accuracy("RK4 32 steps, tol 1e-10", manipulator_options(4, 0, 10, 1));
  print_sweep_accuracy("RKMK4 32 steps, tol 1e-10", manipulator_options(4, 1, 10, 0));
  print_sweep_accuracy("RK6 10 steps, tol 1e-10", manipulator_options(6, 0, 10, 1));
  print_sweep_accuracy("RK6 10 steps, tol 1e-8", manipulator_options(6, 0, 8, 1));
  print_sweep_accuracy("RK8 4 steps, tol 1e-10", manipulator_options(8, 0, 10, 1));
  print_accuracy("steel 4-tendon rod", cosserat::testing::steel_tendon_rod(), kSteelSteps);
  {
    const rod::RodModel m = cosserat::testing::steel_tendon_rod();
    cosserat::Options o = options(kSteelRk8Steps);
    o.integrator.method = ode::Method::kRk8;
    std::printf("  RK8 tip error at %d steps vs RK4 4096 steps: %.3e m\n", kSteelRk8Steps,
                (tip(m, o) - tip(m, options(4096, 1e-10))).norm());
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
