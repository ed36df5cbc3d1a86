#pragma once
/// Helpers shared by the subcommands: value ranges, vectors, actuator lists, count bounds and
/// output destinations.
#include <Eigen/Core>
#include <iosfwd>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "rod/model.hpp"
#include "study/simulation.hpp"
#include "tca/tca.hpp"

namespace tcasim::app {

/// Exit code of an input error (a bad flag or file), as main() maps InputError.
inline constexpr int kExitInputError = 2;

/// Upper bounds of the command-line counts, each with its reason.
/// Fixed steps of the shooting integrator: RK4's error falls like N^-4 and reaches
/// round-off near the 2048 steps of the validation reference; 100000 steps take about a
/// second per solve, beyond that the run only burns time.
inline constexpr int kMaxSteps = 100000;
/// FE elements: quadratic elements reach round-off near 1000 elements on the shipped
/// scenarios (validate_convergence); 10000 keeps one solve within seconds and memory small.
inline constexpr int kMaxElements = 10000;
/// Model evaluations of `tcasim fit` (each a TCA curve, microseconds): 100000 is minutes.
inline constexpr int kMaxEvaluations = 100000;

/// Worker threads of `tcasim sweep --jobs`: more than this many is a typo, not a machine.
inline constexpr int kMaxJobs = 1024;
/// Shards of `tcasim sweep --shard I/N`: a sweep has at most a million points (common/grid.hpp).
inline constexpr long long kMaxShards = 1000000;

/// Time steps of one simulation (study/simulation.hpp).
using study::kMaxTimeSteps;

/// Checks `--duration-s`, `--dt-s` (both > 0, 1 .. kMaxTimeSteps steps) and `--alpha` (in
/// [-0.5, 0]) of `tcasim simulate` and `compare --dynamic`; returns round(duration / dt).
long long require_time_flags(double duration_s, double dt_s, double alpha);

/// Requires lo <= value <= hi for the count given by `flag` (`--steps = 1e9 must be ...`).
void require_count(long long value, const std::string& flag, long long lo, long long hi);

/// Splits `text` at each `delimiter` into its items, refusing an empty item: a leading,
/// doubled or trailing delimiter ("25:", "1,2,", ",1", "a,,b") or an empty text is an
/// InputError naming `flag` and the value, with `rule` (the list's format) and which item is
/// empty. (CLI11's own list splitting silently drops a trailing empty item, so the list
/// options take a string and split it here.)
std::vector<std::string> split_list(const std::string& text, char delimiter,
                                    const std::string& flag, const std::string& rule);

/// Parses "A:B:S" (start, stop, step; the inclusive grid of common/grid.hpp) or a single
/// value "A". `flag` names the option in error messages.
std::vector<double> parse_range(const std::string& text, const std::string& flag);

/// Part I (0-based) of N of a job split (`--shard I/N`).
struct Shard {
  long long index = 0, count = 1;
};
/// Parses "I/N" (integers, 1 <= N <= kMaxShards, 0 <= I < N); InputError naming `flag`
/// with the rule that fails otherwise.
Shard parse_shard(const std::string& text, const std::string& flag);

/// "X,Y,Z" -> vector (InputError naming `flag` unless exactly three finite numbers).
Eigen::Vector3d parse_vector3(const std::string& text, const std::string& flag);

/// Comma-separated actuator names -> model indices (all actuators for an empty text);
/// InputError naming `flag` for an unknown, repeated or empty name ("tca0,").
std::vector<int> actuator_indices(const rod::RodModel& model, const std::string& names,
                                  const std::string& flag);

/// Picks one TCA of a scenario or TCA file (`--tca` id, required when the file has several),
/// applying the optional material and f12-form overrides (rod::select_tca with the flags'
/// names; an empty text is an absent flag). Throws InputError naming the flag.
std::shared_ptr<const tca::Tca> select_tca(const std::string& file, const std::string& id,
                                           const std::string& material_name,
                                           const std::string& f12_form);

/// An output destination: stdout when `path` is empty or "-" (written as it comes), else
/// the file at `path`, written whole by commit() (rod/output_file.hpp): a run that fails
/// before commit() leaves no partial file and any existing file untouched.
class Output {
 public:
  explicit Output(std::string path, std::string flag = "--out");
  std::ostream& stream();
  /// Writes the buffered text to the file atomically (stdout: flushes). Throws InputError
  /// naming the flag when the file cannot be written.
  void commit();

 private:
  std::string path_, flag_;
  std::ostringstream buffer_;
};

}  // namespace tcasim::app
