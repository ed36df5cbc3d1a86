#include "common/convergence.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace tcasim {

std::vector<double> observed_orders(const std::vector<double>& h,
                                    const std::vector<double>& errors) {
  if (h.size() != errors.size()) {
    throw std::invalid_argument(
        fmt::format("observed_orders: {} step sizes but {} errors", h.size(), errors.size()));
  }
  if (h.size() < 2) throw std::invalid_argument("observed_orders: needs at least 2 levels");
  std::vector<double> p;
  p.reserve(h.size() - 1);
  for (std::size_t i = 0; i + 1 < h.size(); ++i) {
    if (!(h[i] > 0.0) || !(h[i + 1] > 0.0) || h[i] == h[i + 1] || !std::isfinite(h[i]) ||
        !std::isfinite(h[i + 1])) {
      throw std::invalid_argument(
          fmt::format("observed_orders: h[{}] = {}, h[{}] = {} must be positive and distinct", i,
                      h[i], i + 1, h[i + 1]));
    }
    const bool usable = errors[i] > 0.0 && errors[i + 1] > 0.0 && std::isfinite(errors[i]) &&
                        std::isfinite(errors[i + 1]);
    p.push_back(usable ? std::log(errors[i] / errors[i + 1]) / std::log(h[i] / h[i + 1])
                       : std::numeric_limits<double>::quiet_NaN());
  }
  return p;
}

}  // namespace tcasim
