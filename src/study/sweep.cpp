#include "study/sweep.hpp"

namespace tcasim::study {

void solve_chunk(const rod::RodModel& model, const Sweep& sweep, IndexRange range,
                 const std::function<void(std::size_t, rod::Result&&)>& on_point) {
  // A cold start for every chunk: fresh loads, solver and state, whatever ran before.
  rod::Loads loads = rod::Loads::from_model(model);
  method::StaticSolver solver(model, sweep.method);
  for (std::size_t k = range.begin; k < range.end; ++k) {
    if (sweep.by_temperature) {
      loads.set_temperature_K(sweep.actuator, sweep.values[k]);
    } else {
      loads.set_tension_N(sweep.actuator, sweep.values[k]);
    }
    on_point(k, solver.solve(loads));
  }
}

void solve_chunks(const rod::RodModel& model, const Sweep& sweep,
                  const std::vector<IndexRange>& chunks, IndexRange which, int jobs,
                  const std::function<void(std::size_t, rod::Result&&)>& on_point,
                  const std::function<void(std::size_t)>& on_chunk_done) {
  run_parallel(which.size(), jobs, [&](std::size_t i) {
    const std::size_t c = which.begin + i;
    solve_chunk(model, sweep, chunks[c], on_point);
    if (on_chunk_done) on_chunk_done(c);
  });
}

}  // namespace tcasim::study
