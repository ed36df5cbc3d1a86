// Google Benchmark of the TCA law: tension(delta, T) runs inside ODE right-hand sides
// (no allocation, no root finding); elongation(F, T) solves Eqs. (2)+(5) by Brent.
#include <benchmark/benchmark.h>

#include "common/units.hpp"
#include "tca/tca.hpp"

namespace {

using namespace tcasim;

tca::Tca make_tca() {
  tca::Material m;
  m.name = "silver-nylon-sun2022";
  m.reference_temperature_K = units::degC_to_K(25.0);
  m.youngs_modulus_Pa.coefficients = {1.198e9};
  m.shear_modulus_Pa.coefficients = {0.2218e9};
  m.diameter.type = tca::DiameterLaw::Type::kRatioPolynomial;
  m.diameter.ratio_polynomial.coefficients = {1.00169, -6.705e-5, 3.542e-6};
  m.min_temperature_K = units::degC_to_K(25.0);
  m.max_temperature_K = units::degC_to_K(160.0);
  tca::Parameters p;
  p.coiled_length_m = 0.110;
  p.fiber_length_m = 0.497;
  p.outer_diameter_m = 0.002;
  p.twist_turns = 300;
  return tca::Tca(p, m);
}

void BM_Tension(benchmark::State& state) {
  const tca::Tca tca = make_tca();
  double delta = 0.01, t_K = units::degC_to_K(100.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(delta);
    benchmark::DoNotOptimize(t_K);
    const tca::TensionState s = tca.tension(delta, t_K);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_Tension);

void BM_Elongation(benchmark::State& state) {
  const tca::Tca tca = make_tca();
  double F = -0.0736, t_K = units::degC_to_K(120.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(F);
    benchmark::DoNotOptimize(t_K);
    const tca::ElongationState e = tca.elongation(F, t_K);
    benchmark::DoNotOptimize(e);
  }
}
BENCHMARK(BM_Elongation);

void BM_SeriesTension(benchmark::State& state) {
  const tca::Tca tca = make_tca();
  const std::vector<tca::Segment> segs = {{0.5, units::degC_to_K(60.0)},
                                          {0.5, units::degC_to_K(120.0)}};
  for (auto _ : state) {
    const tca::SeriesTensionState s = tca::series_tension(tca, 0.03, segs);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_SeriesTension);

}  // namespace

BENCHMARK_MAIN();
