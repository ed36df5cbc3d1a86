#pragma once
/// Helpers shared by the subcommands: value ranges and output destinations.
#include <fstream>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace tcasim::app {

/// Parses "A:B:S" (start, stop, step; stop included when reached within 1e-9 of a step)
/// or a single value "A". `flag` names the option in error messages; step must be > 0
/// and B >= A.
std::vector<double> parse_range(const std::string& text, const std::string& flag);

/// An output stream: the file at `path`, or stdout when path is empty or "-".
class Output {
 public:
  explicit Output(const std::string& path);
  std::ostream& stream();

 private:
  std::unique_ptr<std::ofstream> file_;
};

}  // namespace tcasim::app
