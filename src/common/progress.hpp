#pragma once
/// Progress of a long loop (a sweep's points, a study's solves) on a stream, usually stderr.
/// On a terminal: one line rewritten in place (carriage return) at every update. Elsewhere (a
/// log file, a pipe, ctest): whole lines only, one each time another `line_fraction` of the
/// total is done or `line_seconds` have passed, and always the last, so logs stay readable
/// instead of piling the in-place updates into one line.
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace tcasim {

/// When a non-terminal stream gets a whole line.
struct ProgressOptions {
  double line_fraction = 0.1;  ///< a line per this share of the total (10 %)
  double line_seconds = 5.0;   ///< and at least every this many seconds [s]
};

/// Reports "<label>: <done>/<total> <unit>, <seconds> s".
class ProgressReporter {
 public:
  /// Terminal mode when `stream` is a terminal (isatty).
  ProgressReporter(std::FILE* stream, std::string label, std::size_t total,
                   std::string unit = "points", ProgressOptions options = {});
  /// Explicit mode (tests; `interactive` = terminal mode).
  ProgressReporter(std::FILE* stream, std::string label, std::size_t total, std::string unit,
                   ProgressOptions options, bool interactive);

  /// Reports that `done` of the total are finished (done <= total); prints when due.
  void update(std::size_t done);
  bool interactive() const { return interactive_; }

 private:
  std::FILE* stream_;
  std::string label_, unit_;
  std::size_t total_;
  ProgressOptions options_;
  bool interactive_;
  std::chrono::steady_clock::time_point start_, last_line_;
  std::size_t last_line_done_ = 0;
};

}  // namespace tcasim
