#include "support/finite_difference.hpp"

#include <algorithm>
#include <cmath>

#include "common/finite_difference.hpp"

namespace tcasim::test_support {

double default_relative_step() { return fd::kCentralRelativeStep; }

double central_difference_step(double x, double relative_step) {
  const double h = relative_step * std::max(1.0, std::abs(x));
  // Round h to the spacing actually realised in floating point at x.
  volatile double x_plus = x + h;
  return x_plus - x;
}

double derivative(const std::function<double(double)>& f, double x, double relative_step) {
  const double h = central_difference_step(x, relative_step);
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

Eigen::VectorXd gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                         const Eigen::VectorXd& x, double relative_step) {
  Eigen::VectorXd g(x.size());
  Eigen::VectorXd xp = x;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = central_difference_step(x[j], relative_step);
    xp[j] = x[j] + h;
    const double f_plus = f(xp);
    xp[j] = x[j] - h;
    const double f_minus = f(xp);
    xp[j] = x[j];
    g[j] = (f_plus - f_minus) / (2.0 * h);
  }
  return g;
}

Eigen::MatrixXd jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                         const Eigen::VectorXd& x, double relative_step) {
  Eigen::MatrixXd J;
  Eigen::VectorXd xp = x;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = central_difference_step(x[j], relative_step);
    xp[j] = x[j] + h;
    const Eigen::VectorXd f_plus = f(xp);
    xp[j] = x[j] - h;
    const Eigen::VectorXd f_minus = f(xp);
    xp[j] = x[j];
    if (j == 0) J.resize(f_plus.size(), x.size());
    J.col(j) = (f_plus - f_minus) / (2.0 * h);
  }
  return J;
}

double worst_column_relative_difference(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  double worst = 0.0;
  for (Eigen::Index j = 0; j < B.cols(); ++j) {
    worst = std::max(worst, (A.col(j) - B.col(j)).norm() / B.col(j).norm());
  }
  return worst;
}

}  // namespace tcasim::test_support
