#pragma once
/// Central-difference derivatives for checking analytic derivatives in tests.
///
/// Step rule: h_i = relative_step * max(1, |x_i|), with relative_step = cbrt(eps)
/// ~ 6e-6 by default. Central differences have truncation error ~ h^2 |f'''|/6 and
/// round-off ~ eps |f| / h; h ~ eps^(1/3) balances them, giving an error
/// ~ eps^(2/3) ~ 4e-11 relative for O(1) derivatives. The step is rounded so that
/// x + h and x - h are exactly representable offsets.
#include <Eigen/Core>
#include <functional>

namespace tcasim::test_support {

/// Default relative step: cbrt(machine epsilon).
double default_relative_step();

/// The rule above for one coordinate: relative_step * max(1, |x|).
double central_difference_step(double x, double relative_step = default_relative_step());

/// df/dx of a scalar function of one variable.
double derivative(const std::function<double(double)>& f, double x,
                  double relative_step = default_relative_step());

/// Gradient of a scalar function of a vector.
Eigen::VectorXd gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                         const Eigen::VectorXd& x, double relative_step = default_relative_step());

/// Jacobian d f_i / d x_j of a vector function (f(x).size() rows, x.size() columns).
Eigen::MatrixXd jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                         const Eigen::VectorXd& x, double relative_step = default_relative_step());

/// Worst column-wise relative difference max_j |A_j - B_j| / |B_j| (each column of a
/// Jacobian has its own scale); B is the reference.
double worst_column_relative_difference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

}  // namespace tcasim::test_support
