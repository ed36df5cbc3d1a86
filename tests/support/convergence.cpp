#include "support/convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tcasim::test_support {

std::vector<double> observed_orders(const std::vector<double>& h, const std::vector<double>& errors) {
  if (h.size() != errors.size())
    throw std::invalid_argument(fmt::format("observed_orders: {} step sizes but {} errors", h.size(),
                                            errors.size()));
  if (h.size() < 2) throw std::invalid_argument("observed_orders: needs at least 2 levels");
  std::vector<double> p;
  p.reserve(h.size() - 1);
  for (std::size_t i = 0; i + 1 < h.size(); ++i) {
    if (!(h[i] > 0.0) || !(h[i + 1] > 0.0) || h[i] == h[i + 1] || !std::isfinite(h[i]))
      throw std::invalid_argument(
          fmt::format("observed_orders: h[{}] = {}, h[{}] = {} must be positive and distinct", i,
                      h[i], i + 1, h[i + 1]));
    const bool usable = errors[i] > 0.0 && errors[i + 1] > 0.0 && std::isfinite(errors[i]) &&
                        std::isfinite(errors[i + 1]);
    p.push_back(usable ? std::log(errors[i] / errors[i + 1]) / std::log(h[i] / h[i + 1])
                       : std::numeric_limits<double>::quiet_NaN());
  }
  return p;
}

std::string convergence_table(const std::vector<double>& h, const std::vector<double>& errors) {
  const std::vector<double> p = observed_orders(h, errors);
  std::string out = fmt::format("{:>5}  {:>12}  {:>12}  {:>8}\n", "level", "h", "error", "order");
  for (std::size_t i = 0; i < h.size(); ++i) {
    out += fmt::format("{:>5}  {:>12.5e}  {:>12.5e}  {:>8}\n", i, h[i], errors[i],
                       i == 0 ? std::string("-") : fmt::format("{:.4f}", p[i - 1]));
  }
  return out;
}

::testing::AssertionResult OrderInBracket(const std::vector<double>& h,
                                          const std::vector<double>& errors, double expected_order,
                                          double tolerance, int first_checked) {
  const std::vector<double> p = observed_orders(h, errors);
  const double lo = expected_order - tolerance;
  const double hi = expected_order + tolerance;
  std::string bad;
  for (std::size_t i = static_cast<std::size_t>(std::max(first_checked, 0)); i < p.size(); ++i) {
    if (!(p[i] >= lo && p[i] <= hi))
      bad += fmt::format(" order {:.4f} between levels {} and {};", p[i], i, i + 1);
  }
  const std::string what = fmt::format("observed orders (from pair {}) vs bracket [{}, {}]",
                                       first_checked, lo, hi);
  if (bad.empty()) return ::testing::AssertionSuccess() << what << " hold\n"
                                                        << convergence_table(h, errors);
  return ::testing::AssertionFailure() << what << " violated:" << bad << "\n"
                                       << convergence_table(h, errors);
}

void ExpectOrderInBracket(const std::vector<double>& h, const std::vector<double>& errors,
                          double expected_order, double tolerance, int first_checked) {
  EXPECT_TRUE(OrderInBracket(h, errors, expected_order, tolerance, first_checked));
}

}  // namespace tcasim::test_support
