#pragma once
/// Observed convergence orders and a two-sided order gate for tests.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/convergence.hpp"

namespace tcasim::test_support {

/// The one definition of observed orders (common/convergence.hpp).
using tcasim::observed_orders;

/// Table with columns level, h, error, observed order (the order of level i is the
/// one between levels i-1 and i).
std::string convergence_table(const std::vector<double>& h, const std::vector<double>& errors);

/// Success iff every observed order with index >= first_checked lies in
/// [expected_order - tolerance, expected_order + tolerance] (two-sided: an order far
/// above theory means the test measures the wrong thing). The failure message
/// prints the whole table.
::testing::AssertionResult OrderInBracket(const std::vector<double>& h,
                                          const std::vector<double>& errors, double expected_order,
                                          double tolerance, int first_checked = 0);

/// EXPECT_TRUE(OrderInBracket(...)); use SCOPED_TRACE at the call site for context.
void ExpectOrderInBracket(const std::vector<double>& h, const std::vector<double>& errors,
                          double expected_order, double tolerance, int first_checked = 0);

}  // namespace tcasim::test_support
