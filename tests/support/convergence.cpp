#include "support/convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tcasim::test_support {

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
  const std::string what =
      fmt::format("observed orders (from pair {}) vs bracket [{}, {}]", first_checked, lo, hi);
  if (bad.empty())
    return ::testing::AssertionSuccess() << what << " hold\n" << convergence_table(h, errors);
  return ::testing::AssertionFailure() << what << " violated:" << bad << "\n"
                                       << convergence_table(h, errors);
}

void ExpectOrderInBracket(const std::vector<double>& h, const std::vector<double>& errors,
                          double expected_order, double tolerance, int first_checked) {
  EXPECT_TRUE(OrderInBracket(h, errors, expected_order, tolerance, first_checked));
}

}  // namespace tcasim::test_support
