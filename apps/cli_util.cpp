#include "apps/cli_util.hpp"

#include <cmath>
#include <iostream>

#include "common/error.hpp"

namespace tcasim::app {

namespace {

double parse_number(const std::string& s, const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v)) {
    throw InputError(flag, text, "must be a number or a range START:STOP:STEP");
  }
  return v;
}

}  // namespace

std::vector<double> parse_range(const std::string& text, const std::string& flag) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() == 1) return {parse_number(parts[0], flag, text)};
  if (parts.size() != 3) throw InputError(flag, text, "must be a number or a range START:STOP:STEP");
  const double a = parse_number(parts[0], flag, text);
  const double b = parse_number(parts[1], flag, text);
  const double step = parse_number(parts[2], flag, text);
  if (!(step > 0.0)) throw InputError(flag, text, "must have a step > 0");
  if (b < a) throw InputError(flag, text, "must have STOP >= START");
  const double count = std::floor((b - a) / step + 1e-9);
  if (count > 1e6) throw InputError(flag, text, "has more than a million points");
  std::vector<double> values;
  for (int k = 0; k <= static_cast<int>(count); ++k) values.push_back(a + k * step);
  return values;
}

Output::Output(const std::string& path) {
  if (path.empty() || path == "-") return;
  file_ = std::make_unique<std::ofstream>(path);
  if (!*file_) throw InputError("--out", path, "cannot be opened for writing");
}

std::ostream& Output::stream() { return file_ ? *file_ : std::cout; }

}  // namespace tcasim::app
