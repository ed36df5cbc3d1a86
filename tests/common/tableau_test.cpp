/// Butcher tableaus of the fixed-step integrators against the order conditions (rooted
/// trees), in its own binary unit: ode_test.cpp replaces the global allocator.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "common/ode.hpp"

namespace tcasim::ode {
namespace {

/// Rooted trees up to `max_order` nodes (Butcher's order conditions): each tree is its
/// order, its density gamma and its children (indices of earlier trees, non-increasing).
struct RootedTree {
  int order = 1;
  double gamma = 1.0;
  std::vector<int> children;
};
std::vector<RootedTree> rooted_trees(int max_order) {
  std::vector<RootedTree> trees{RootedTree{}};
  for (int n = 2; n <= max_order; ++n) {
    const int before = static_cast<int>(trees.size());
    // Multisets of earlier trees with orders summing to n - 1, as non-increasing index lists.
    std::vector<int> pick;
    const auto extend = [&](auto&& self, int remaining, int max_index) -> void {
      if (remaining == 0) {
        RootedTree t;
        t.order = n;
        t.gamma = n;
        for (int u : pick) t.gamma *= trees[u].gamma;
        t.children = pick;
        trees.push_back(t);
        return;
      }
      for (int u = max_index; u >= 0; --u) {
        if (trees[u].order > remaining) continue;
        pick.push_back(u);
        self(self, remaining - trees[u].order, u);
        pick.pop_back();
      }
    };
    extend(extend, n - 1, before - 1);
  }
  return trees;
}

/// Largest |b . Phi(t) - 1/gamma(t)| over the trees of each order 1..max_order.
std::vector<double> order_condition_defects(const Tableau& tab, int max_order) {
  const int s = tab.stages;
  const std::vector<RootedTree> trees = rooted_trees(max_order);
  std::vector<Eigen::VectorXd> phi;  // stage weights Phi_i(t)
  std::vector<double> defect(max_order + 1, 0.0);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> A(
      tab.a.data(), s, s);
  const Eigen::Map<const Eigen::VectorXd> b(tab.b.data(), s);
  for (const RootedTree& t : trees) {
    Eigen::VectorXd p = Eigen::VectorXd::Ones(s);
    for (int u : t.children) p = p.cwiseProduct(A * phi[u]);
    phi.push_back(p);
    defect[t.order] = std::max(defect[t.order], std::abs(b.dot(p) - 1.0 / t.gamma));
  }
  return defect;
}

TEST(OdeTableau, RungeKuttaTableausSatisfyExactlyTheOrderConditionsOfTheirOrder) {
  // 1, 1, 2, 4, 9, 20, 48, 115, 286 rooted trees of orders 1..9 (OEIS A000081).
  const std::vector<RootedTree> trees = rooted_trees(9);
  std::vector<int> per_order(10, 0);
  for (const RootedTree& t : trees) ++per_order[t.order];
  EXPECT_EQ(per_order, (std::vector<int>{0, 1, 1, 2, 4, 9, 20, 48, 115, 286}));
  /// Round-off of sums of products of coefficients of size <= 15.
  constexpr double kExact = 1e-13;
  /// A violated condition of the next order is far above round-off.
  constexpr double kViolated = 1e-6;
  for (Method m : {Method::kRk4, Method::kRk6, Method::kRk8}) {
    SCOPED_TRACE(to_string(m));
    const Tableau tab = tableau(m);
    const int p = order_of(m);
    ASSERT_EQ(static_cast<int>(tab.a.size()), tab.stages * tab.stages);
    const std::vector<double> defect = order_condition_defects(tab, p + 1);
    for (int q = 1; q <= p; ++q) EXPECT_LE(defect[q], kExact) << "order " << q;
    EXPECT_GE(defect[p + 1], kViolated) << "order " << p + 1 << " conditions all hold";
  }
  EXPECT_EQ(tableau(Method::kRk8).stages, 11);
  EXPECT_THROW(tableau(Method::kCvode), InputError);
}

}  // namespace
}  // namespace tcasim::ode
