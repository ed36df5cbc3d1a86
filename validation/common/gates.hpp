#pragma once
/// Gates of a validation program: named checks with a measured value and a bound. Each
/// program records its gates here, prints them, writes OUT/gates.csv (read by the report,
/// scripts/make_report.py) and exits with exit_code(): ctest and the main job see the
/// same verdict.
#include <string>
#include <vector>

namespace tcasim::validation {

/// One gate's outcome.
struct GateRecord {
  std::string name;      ///< what is checked, e.g. "circular / sun2022: radius decreases"
  std::string measured;  ///< the measured value, with unit
  std::string bound;     ///< the rule, e.g. "<= 1e-9 L" or "in [3.7, 4.3]"
  bool passed;
};

/// Collects gates, prints each as it is recorded.
class Gates {
 public:
  explicit Gates(std::string program) : program_(std::move(program)) {}

  /// Records a gate with a verdict computed by the caller; returns `passed`.
  bool check(const std::string& name, bool passed, const std::string& measured, const std::string& bound);
  /// measured <= bound (NaN fails).
  bool at_most(const std::string& name, double measured, double bound, const std::string& unit = "");
  /// lo <= measured <= hi (NaN fails).
  bool within(const std::string& name, double measured, double lo, double hi);

  const std::vector<GateRecord>& records() const { return records_; }
  int failures() const;
  /// Writes OUT/gates.csv with columns program,gate,measured,bound,passed.
  void write_csv(const std::string& out_dir) const;
  /// Prints the verdict line and returns 0 when every gate passed, 1 otherwise.
  int finish() const;

 private:
  std::string program_;
  std::vector<GateRecord> records_;
};

}  // namespace tcasim::validation
