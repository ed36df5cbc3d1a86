#include "common/grid.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"

namespace tcasim {

std::vector<double> inclusive_grid(double lo, double hi, double step, const std::string& key) {
  const std::string text = fmt::format("{}:{}:{}", lo, hi, step);
  require(step > 0.0, key, text, "needs a step > 0");
  require(lo <= hi, key, text, "needs start <= stop");
  // Tolerance for including the end point: decimal steps like 0.1 do not sum exactly.
  constexpr double kEndSlack = 1e-6;
  const double count = std::floor((hi - lo) / step + kEndSlack);
  require(count < 1e6, key, text, "gives more than a million points");
  std::vector<double> grid;
  grid.reserve(static_cast<std::size_t>(count) + 1);
  for (long i = 0; i <= static_cast<long>(count); ++i)
    grid.push_back(lo + static_cast<double>(i) * step);
  return grid;
}

}  // namespace tcasim
