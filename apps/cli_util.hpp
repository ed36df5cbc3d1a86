#pragma once
/// Helpers shared by the subcommands: value ranges and output destinations.
#include <fstream>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "tca/tca.hpp"

namespace tcasim::app {

/// Parses "A:B:S" (start, stop, step; the inclusive grid of common/grid.hpp) or a single
/// value "A". `flag` names the option in error messages.
std::vector<double> parse_range(const std::string& text, const std::string& flag);

/// Picks one TCA of a scenario or TCA file (`--tca` id, required when the file has several),
/// applying the optional material and f12-form overrides. Throws InputError naming the flag.
std::shared_ptr<const tca::Tca> select_tca(const std::string& file, const std::string& id,
                                           const std::string& material_name,
                                           const std::string& f12_form);

/// An output stream: the file at `path`, or stdout when path is empty or "-".
class Output {
 public:
  explicit Output(const std::string& path);
  std::ostream& stream();

 private:
  std::unique_ptr<std::ofstream> file_;
};

}  // namespace tcasim::app
