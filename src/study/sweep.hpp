#pragma once
/// A sweep of one actuator's temperature or tension with either forward solver, in chunks:
/// each chunk starts cold (fresh loads, solver and state) and warm-starts its points in
/// order, so a chunk's numbers do not depend on which thread, process or shard solves it
/// (`tcasim sweep --chunk/--jobs/--shard`, `tcasim.sweep` in Python).
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "common/parallel.hpp"
#include "method/method.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::study {

/// Points of a sweep chunk by default (`tcasim sweep --chunk`): each chunk starts cold and
/// warm-starts its points in order, so the chunks are independent and the threads of
/// `--jobs` and the shards of `--shard` give the numbers of the serial run, bit for bit. With
/// 100 points the extra cold starts cost little: +1.4 % CPU time on a 1001-point shooting
/// sweep of the circular manipulator (docs/scenario-format.md "Sweeps in chunks").
inline constexpr long long kDefaultSweepChunk = 100;

/// What a sweep varies and how it solves each point.
struct Sweep {
  std::size_t actuator = 0;    ///< index into RodModel::actuators
  bool by_temperature = true;  ///< true: every segment's temperature [K]; false: tension [N]
  std::vector<double> values;  ///< temperatures [K] or tensions [N], in sweep order
  /// The method and its settings (method/method.hpp).
  method::StaticOptions method = cosserat::Options{};
};

/// Solves the points range.begin ... range.end - 1 of `sweep`: cold at the first, each
/// later one warm-started from its predecessor. Calls on_point(k, result) after point k.
void solve_chunk(const rod::RodModel& model, const Sweep& sweep, IndexRange range,
                 const std::function<void(std::size_t, rod::Result&&)>& on_point);

/// Solves the chunks chunks[c] for c in `which` on `jobs` threads (run_parallel): every
/// chunk with solve_chunk, on_point called from the solving thread (it must be thread
/// safe), on_chunk_done(c) after chunk c's last point.
void solve_chunks(const rod::RodModel& model, const Sweep& sweep,
                  const std::vector<IndexRange>& chunks, IndexRange which, int jobs,
                  const std::function<void(std::size_t, rod::Result&&)>& on_point,
                  const std::function<void(std::size_t)>& on_chunk_done = {});

}  // namespace tcasim::study
