#pragma once
/// Gates of a validation program: named checks with a measured value and a bound. Each
/// program records its gates here, prints them, writes OUT/gates.csv (read by the report,
/// scripts/make_report.py) and exits with finish(): ctest and the main job see the
/// same verdict.
///
/// A gate set cannot pass empty or by omission:
///  - finish() fails when no gate was recorded;
///  - a non-finite measurement fails in every gate kind (a NaN, inf or -inf number, and a
///    check() whose measured text holds one of the words nan, inf, infinity);
///  - a non-finite bound fails (it would make a gate that cannot fail);
///  - expect_count() fails when fewer scenarios or points ran than the program declared;
///  - not_run() records a case that was not run (e.g. a scenario a solver does not
///    support) as a failure, with its reason.
#include <cstddef>
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

  /// Records a gate with a verdict computed by the caller; returns the recorded verdict:
  /// `passed`, and false when `measured` names a non-finite number (nan, inf, infinity).
  bool check(const std::string& name, bool passed, const std::string& measured,
             const std::string& bound);
  /// measured <= bound; fails when either is not finite.
  bool at_most(const std::string& name, double measured, double bound,
               const std::string& unit = "");
  /// lo <= measured <= hi; fails when any of them is not finite.
  bool within(const std::string& name, double measured, double lo, double hi);
  /// ran >= expected: `what` (e.g. "scenarios") counts the cases the program declared it
  /// would run; fewer ran means a case was lost silently. Fails when expected is 0 too
  /// (a program that expects nothing checks nothing).
  bool expect_count(const std::string& what, std::size_t ran, std::size_t expected);
  /// Records a case that was not run as a failed gate "<name>: not run" with the reason.
  void not_run(const std::string& name, const std::string& reason);

  const std::vector<GateRecord>& records() const { return records_; }
  int failures() const;
  /// Writes OUT/gates.csv with columns program,gate,measured,bound,passed.
  void write_csv(const std::string& out_dir) const;
  /// Prints the verdict line and returns 0 when at least one gate was recorded and every
  /// gate passed, 1 otherwise.
  int finish() const;

 private:
  std::string program_;
  std::vector<GateRecord> records_;
};

}  // namespace tcasim::validation
