#pragma once
/// Observed convergence orders: one definition for tests, validation programs and the CLI.
#include <vector>

namespace tcasim {

/// Observed orders between successive levels:
///   p_i = log(e_i / e_{i+1}) / log(h_i / h_{i+1}),  i = 0..n-2,
/// for any ratios of h (not only halving). A pair with a non-positive or non-finite
/// error gives NaN (which fails any bracket). Throws std::invalid_argument if the
/// sizes differ, fewer than 2 levels are given, or h is not positive, finite and distinct
/// between successive levels.
std::vector<double> observed_orders(const std::vector<double>& h,
                                    const std::vector<double>& errors);

}  // namespace tcasim
