#pragma once
/// Inclusive uniform grids for sweeps (temperatures, tensions).
#include <string>
#include <vector>

namespace tcasim {

/// lo, lo + step, ..., up to hi (included when within step/1e6 of the grid).
/// Throws InputError(key, "lo:hi:step", rule) unless step > 0, lo <= hi and the grid has
/// at most a million points.
std::vector<double> inclusive_grid(double lo, double hi, double step, const std::string& key);

}  // namespace tcasim
