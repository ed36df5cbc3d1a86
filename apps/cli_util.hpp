#pragma once
/// Helpers of the command line only: value ranges, vectors, shards, TCA choice and output
/// destinations. The checks of options the Python module shares live in study/options.hpp.
#include <Eigen/Core>
#include <iosfwd>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "rod/model.hpp"
#include "study/options.hpp"
#include "tca/tca.hpp"

namespace tcasim::app {

/// Exit code of an input error (a bad flag or file), as main() maps InputError.
inline constexpr int kExitInputError = 2;

/// The bounds and checks shared with the Python module (study/options.hpp).
using study::actuator_indices;
using study::kMaxElements;
using study::kMaxJobs;
using study::kMaxSteps;
using study::kMaxTimeSteps;
using study::require_count;
using study::split_list;

/// Model evaluations of `tcasim fit` (each a TCA curve, microseconds): 100000 is minutes.
inline constexpr int kMaxEvaluations = 100000;
/// Shards of `tcasim sweep --shard I/N`: a sweep has at most a million points (common/grid.hpp).
inline constexpr long long kMaxShards = 1000000;

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

/// Exactly one time-step mode of `simulate` and `compare --dynamic`: fixed (--dt-s, given as
/// `dt_text` when `dt_given`) or adaptive (--rtol); InputError naming --dt-s otherwise.
void require_one_time_step_mode(bool dt_given, const std::string& dt_text, bool rtol_given);

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
