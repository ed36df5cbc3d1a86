// FE dynamics benchmark: one time step of the paper's manipulator
// (validation/scenarios/circular-manipulator.json) with its TCA replaced by a tension drive at
// the tension of its static FE solution, 64 quadratic elements, dt = 1 ms, rho_inf = 0.9: the
// rod starts at rest without tension and every benchmark iteration is one step of the
// resulting motion. Counter newton_iterations: per step.
// Run: build/bench/bench_beam_fe_dynamics --benchmark_repetitions=5
//        --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/dynamics.hpp"
#include "rod/scenario.hpp"

namespace {

using namespace tcasim;

rod::RodModel tension_driven_manipulator() {
  rod::RodModel m = rod::read_scenario(std::string(TCASIM_SOURCE_DIR) +
                                       "/validation/scenarios/circular-manipulator.json");
  beam_fe::Options so;
  so.elements = 64;
  beam_fe::State st;
  const beam_fe::Summary s = beam_fe::solve(m, so, st);
  const double tension = s.converged() ? st.tensions_N[0] : 0.0;
  for (rod::Actuator& a : m.actuators) {
    a.drive.type = rod::Drive::Type::kTension;
    a.drive.tension_N = tension;
    a.rest_length_m += a.pre_elongation_m;  // the path length: as a tension-driven string
  }
  return m;
}

void BM_ManipulatorTimeStep(benchmark::State& state) {
  static const rod::RodModel m = tension_driven_manipulator();
  beam_fe::DynamicsOptions o;
  o.elements = 64;
  o.order = 2;
  o.dt_s = 1e-3;
  o.rho_inf = 0.9;
  beam_fe::BeamDynamics d(m, o);
  rod::Loads loads = rod::Loads::from_model(m);
  const double tension = loads.actuators[0].tension_N;
  loads.actuators[0].tension_N = 0.0;
  if (!d.initialize(loads).converged()) state.SkipWithError("static state failed");
  loads.actuators[0].tension_N = tension;
  long long iterations = 0;
  for (auto _ : state) {
    const beam_fe::BeamDynamicsSummary s = d.step(loads);
    iterations += s.iterations;
    if (!s.converged()) state.SkipWithError("a time step failed");
  }
  state.counters["newton_iterations"] =
      static_cast<double>(iterations) / static_cast<double>(state.iterations());
  state.counters["tension_N"] = tension;
}
BENCHMARK(BM_ManipulatorTimeStep)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
