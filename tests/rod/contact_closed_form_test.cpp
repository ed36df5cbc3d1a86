// The contact closed forms of rod/closed_form.hpp against independent numerical solutions of
// the same small-slope problems (Euler-Bernoulli beam elements with a unilateral constraint
// at the nodes, solved by a primal active set), and the wrap's lift-off angle against a
// shooting solution of the elastica under tension. None of the checks evaluates a closed
// form to get its own reference.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "common/error.hpp"
#include "rod/closed_form.hpp"

namespace tcasim::rod {
namespace {

/// A small-slope beam on [0, L] of bending stiffness B in n equal cubic Hermite elements
/// (nodal w and w'), under a uniform load p per length (upward positive), a tip force P
/// (upward), optional base conditions, and the unilateral constraint w(x_i) >= g(x_i) at
/// every node i where g is finite. Minimizes 1/2 w^T K w - f^T w subject to the constraints
/// by a primal active set method (exact on each active set; one node added or dropped per
/// step until no force pulls and no node penetrates). The elements are exact for cubic deflections
/// and, with consistent loads, give exact nodal values for any polynomial load, so the error comes
/// from the contact being held at nodes only.
struct NodalContactBeam {
  double B = 1.0, L = 1.0, p = 0.0, P = 0.0;
  int n = 100;
  std::optional<double> base_w, base_slope;                              ///< prescribed w(0), w'(0)
  std::function<double(double)> gap = [](double) { return -HUGE_VAL; };  ///< g(x)

  Eigen::VectorXd w;         ///< nodal deflections and slopes (2 (n + 1))
  Eigen::VectorXd lambda;    ///< nodal contact forces (n + 1), >= 0
  Eigen::VectorXd reaction;  ///< K w - f at the base dofs (w, w'): what the support applies

  double h() const { return L / n; }
  /// Relative round-off of a solve, n^4 eps (the stiffness's condition number grows as n^4).
  double round_off() const { return std::pow(n, 4) * std::numeric_limits<double>::epsilon(); }
  double x(int i) const { return h() * i; }

  void solve() {
    const int N = 2 * (n + 1);
    std::vector<Eigen::Triplet<double>> kt;
    Eigen::VectorXd f = Eigen::VectorXd::Zero(N);
    const double e = h();
    Eigen::Matrix4d k;
    k << 12, 6 * e, -12, 6 * e, 6 * e, 4 * e * e, -6 * e, 2 * e * e, -12, -6 * e, 12, -6 * e, 6 * e,
        2 * e * e, -6 * e, 4 * e * e;
    k *= B / (e * e * e);
    const Eigen::Vector4d fe(p * e / 2, p * e * e / 12, p * e / 2, -p * e * e / 12);
    for (int el = 0; el < n; ++el) {
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) kt.emplace_back(2 * el + a, 2 * el + b, k(a, b));
      f.segment<4>(2 * el) += fe;
    }
    f[2 * n] += P;
    Eigen::SparseMatrix<double> K(N, N);
    K.setFromTriplets(kt.begin(), kt.end());
    std::vector<bool> active(n + 1, false);
    lambda = Eigen::VectorXd::Zero(n + 1);
    // Solves on the active set: the fixed dofs (base conditions, active nodes) eliminated
    // symmetrically (their rows and columns replaced by the identity).
    auto solve_on = [&](const std::vector<bool>& act) {
      Eigen::VectorXd value = Eigen::VectorXd::Zero(N);
      std::vector<bool> fixed(N, false);
      if (base_w) fixed[0] = true, value[0] = *base_w;
      if (base_slope) fixed[1] = true, value[1] = *base_slope;
      for (int i = 0; i <= n; ++i) {
        if (act[i] && !fixed[2 * i]) fixed[2 * i] = true, value[2 * i] = gap(x(i));
      }
      std::vector<Eigen::Triplet<double>> at;
      Eigen::VectorXd b = f - K * value;
      for (int c = 0; c < N; ++c) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
          if (!fixed[it.row()] && !fixed[it.col()]) at.emplace_back(it.row(), it.col(), it.value());
        }
        if (fixed[c]) at.emplace_back(c, c, 1.0), b[c] = value[c];
      }
      Eigen::SparseMatrix<double> A(N, N);
      A.setFromTriplets(at.begin(), at.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
      w = ldlt.solve(b);
      const Eigen::VectorXd r = K * w - f;  // K w = f + support forces: what they apply
      reaction = r.head<2>();
      for (int i = 0; i <= n; ++i) lambda[i] = act[i] && !(i == 0 && base_w) ? r[2 * i] : 0.0;
    };
    // Primal active set, one change per step (finite for this convex problem): drop the
    // node with the most negative force, else add the most penetrating one.
    for (int it = 0; it < 20 * (n + 1); ++it) {
      solve_on(active);
      int drop = -1, add = -1;
      // Round-off of a solve: the stiffness's condition number grows as n^4.
      double worst_lambda = 0.0, worst_gap = -round_off() * w.lpNorm<Eigen::Infinity>();
      for (int i = 0; i <= n; ++i) {
        const double g = gap(x(i));
        if (!std::isfinite(g) || (i == 0 && base_w)) continue;
        if (active[i] && lambda[i] < worst_lambda) worst_lambda = lambda[i], drop = i;
        if (!active[i] && w[2 * i] - g < worst_gap) worst_gap = w[2 * i] - g, add = i;
      }
      if (drop >= 0) {
        active[drop] = false;
      } else if (add >= 0) {
        active[add] = true;
      } else {
        return;
      }
    }
    ADD_FAILURE() << "active set did not settle";
  }
};

/// The heavy rod clamped at H above a floor: the beam's clamp force and moment and its
/// first node on the floor against heavy_rod_on_floor, to within the touchdown's
/// localization at the nodes (one element).
TEST(ContactClosedForm, HeavyRodOnFloorMatchesNodalContactBeam) {
  for (const bool pinned : {false, true}) {
    const double B = 2.0, q = 3.0, H = 0.5;
    const HeavyRodOnFloor cf = heavy_rod_on_floor(B, q, H, pinned);
    NodalContactBeam beam;
    beam.B = B;
    beam.p = -q;
    beam.L = 2.5 * cf.free_span_m;  // a long flat part; its end is free
    beam.n = 500;
    beam.base_w = H;
    if (!pinned) beam.base_slope = 0.0;
    beam.gap = [](double) { return 0.0; };
    beam.solve();
    int first = -1;
    for (int i = 1; i <= beam.n && first < 0; ++i) {
      if (beam.lambda[i] > 0.0) first = i;
    }
    ASSERT_GT(first, 0);
    const double h = beam.h();
    // The touchdown lies within one element of the first loaded node.
    EXPECT_NEAR(beam.x(first), cf.free_span_m, h) << (pinned ? "pinned" : "clamped");
    // A touchdown misplaced by dl moves the base force by q dl and the moment by q l dl.
    EXPECT_NEAR(beam.reaction[0], cf.base_force_N, q * h) << (pinned ? "pinned" : "clamped");
    EXPECT_NEAR(std::abs(beam.reaction[1]), cf.base_moment_Nm, q * cf.free_span_m * h)
        << (pinned ? "pinned" : "clamped");
    // The point force: the floor's total force less the weight of the flat part from the
    // first loaded node on (q per length); a first node misplaced by up to one element and
    // the half-element loads at the ends change it by up to 2 q h.
    const double point = beam.lambda.sum() - q * (beam.L - beam.x(first));
    EXPECT_NEAR(point, cf.touchdown_force_N, 2.0 * q * h) << (pinned ? "pinned" : "clamped");
    // The free span's shape: heights within the touchdown's effect (slope times one element).
    for (int i = 0; i < first; i += 25) {
      EXPECT_NEAR(beam.w[2 * i], heavy_rod_on_floor_height_m(B, q, H, beam.x(i), pinned),
                  cf.max_slope * h)
          << "x = " << beam.x(i);
    }
    // Largest slope of the free span.
    double slope = 0.0;
    for (int i = 0; i < first; ++i) slope = std::max(slope, std::abs(beam.w[2 * i + 1]));
    EXPECT_NEAR(slope, cf.max_slope, 1e-3 * cf.max_slope + q * cf.free_span_m * h * h / B);
  }
}

/// The cantilever tangent to a cylinder: below the onset the beam never touches; above it,
/// the beam's nodal contact forces add up to F, concentrated at the lift-off, and the tip
/// deflection matches.
TEST(ContactClosedForm, CantileverOnCylinderMatchesNodalContactBeam) {
  const double B = 0.5, L = 0.2, R = 5.0;
  const double onset = B / (R * L);
  for (const double factor : {0.8, 1.5, 3.0, 10.0}) {
    const double F = factor * onset;
    const CantileverOnCylinder cf = cantilever_on_cylinder(B, L, R, F);
    EXPECT_DOUBLE_EQ(cf.onset_force_N, onset);
    NodalContactBeam beam;
    beam.B = B;
    beam.L = L;
    beam.P = -F;
    beam.n = 400;
    beam.base_w = 0.0;
    beam.base_slope = 0.0;
    beam.gap = [R](double x) { return x > 0.0 ? -x * x / (2.0 * R) : -HUGE_VAL; };
    beam.solve();
    const double h = beam.h();
    const double total = beam.lambda.sum();
    EXPECT_EQ(cf.touching, total > 0.0) << factor;
    if (!cf.touching) {
      EXPECT_NEAR(-beam.w[2 * beam.n], cf.tip_deflection_m, beam.round_off() * cf.tip_deflection_m);
      continue;
    }
    // Equilibrium of the discrete beam: the cylinder and the clamp together carry F.
    EXPECT_NEAR(total + beam.reaction[0], F, beam.round_off() * F) << factor;
    // The cylinder's force sits at the lift-off: the resultant's line of action (its first
    // moment over the total) lies at a, to within the few elements over which the nodal
    // constraint smears the point force (a Hermite beam held at nodes cannot carry the
    // continuous solution's pressure-free wrap exactly: its spline end effect decays by a
    // factor of about 0.27 per element).
    double first_moment = 0.0;
    for (int i = 0; i <= beam.n; ++i) first_moment += beam.lambda[i] * beam.x(i);
    EXPECT_NEAR(first_moment / total, cf.lift_off_m, 8 * h) << factor;
    // Tip deflection: the lift-off misplaced by h changes it by about h times the slope
    // difference there, below L h / R.
    EXPECT_NEAR(-beam.w[2 * beam.n], cf.tip_deflection_m, L * h / R) << factor;
    // The clamp holds the moment B / R and no force.
    EXPECT_NEAR(std::abs(beam.reaction[1]), cf.clamp_moment_Nm, F * h) << factor;
  }
}

/// The propped cantilever: the elements are exact for a point load at a node, so the
/// support's force equals the closed form to round-off (n^4 eps).
TEST(ContactClosedForm, ProppedCantileverReactionMatchesBeam) {
  const double B = 3.0, L = 1.2, P = 2.0;
  for (const int node : {40, 70, 100}) {
    NodalContactBeam beam;
    beam.B = B;
    beam.L = L;
    beam.P = -P;
    beam.n = 100;
    beam.base_w = 0.0;
    beam.base_slope = 0.0;
    beam.gap = [&](double x) { return std::abs(x - beam.x(node)) < 1e-12 ? 0.0 : -HUGE_VAL; };
    beam.solve();
    const double a = beam.x(node);
    const double R = propped_cantilever_reaction_N(P, L, a);
    EXPECT_NEAR(beam.lambda[node], R, beam.round_off() * R) << a;
  }
  EXPECT_DOUBLE_EQ(propped_cantilever_reaction_N(P, L, L), P);
  EXPECT_THROW(propped_cantilever_reaction_N(P, L, 0.0), DomainError);
  EXPECT_THROW(propped_cantilever_reaction_N(P, L, 1.5 * L), DomainError);
}

/// The free part of a rod pulled over a cylinder: the elastica B theta'' = T sin theta
/// (theta from the far direction) leaving the arc with curvature 1 / rho. Only one angle
/// theta_d leads to a straight far part; a larger one turns over, a smaller one turns away.
/// Bisection on that behaviour (RK4) finds it without the first integral.
TEST(ContactClosedForm, WrapLiftOffAngleMatchesElasticaShooting) {
  const double B = 0.02, rho = 0.05;
  for (const double T : {40.0, 10.0, 2.5}) {  // B / (4 rho^2) = 2 N
    const std::optional<WrapOnCylinder> cf = rod_wrapped_on_cylinder(B, T, rho);
    ASSERT_TRUE(cf.has_value()) << T;
    // +1: theta crosses zero (too little curvature for the angle: the start angle is too
    // small, the rod overshoots the far direction); -1: theta' turns positive first (the
    // angle is too large).
    auto fate = [&](double theta0) {
      const double k = std::sqrt(B / T);  // the boundary-layer length
      const double ds = k / 2000.0;
      double th = theta0, dth = -1.0 / rho;
      auto f = [&](double a, double da, double& fa, double& fda) {
        fa = da;
        fda = T / B * std::sin(a);
      };
      for (int i = 0; i < 2000 * 60; ++i) {
        double k1a, k1b, k2a, k2b, k3a, k3b, k4a, k4b;
        f(th, dth, k1a, k1b);
        f(th + 0.5 * ds * k1a, dth + 0.5 * ds * k1b, k2a, k2b);
        f(th + 0.5 * ds * k2a, dth + 0.5 * ds * k2b, k3a, k3b);
        f(th + ds * k3a, dth + ds * k3b, k4a, k4b);
        th += ds / 6 * (k1a + 2 * k2a + 2 * k3a + k4a);
        dth += ds / 6 * (k1b + 2 * k2b + 2 * k3b + k4b);
        if (th < 0.0) return +1;
        if (dth > 0.0) return -1;
      }
      return 0;
    };
    double lo = 1e-9, hi = M_PI - 1e-9;
    ASSERT_EQ(fate(lo), +1);
    ASSERT_EQ(fate(hi), -1);
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (fate(mid) > 0 ? lo : hi) = mid;
    }
    EXPECT_NEAR(0.5 * (lo + hi), cf->lift_off_angle_rad, 1e-6) << T;
    // The statics at the lift-off: the free part's force T, split along the tangent and
    // the normal of the arc there.
    EXPECT_NEAR(cf->axial_force_N, T * std::cos(cf->lift_off_angle_rad), 1e-12 * T);
    EXPECT_NEAR(cf->point_force_N, T * std::sin(cf->lift_off_angle_rad), 1e-12 * T);
    EXPECT_NEAR(cf->pressure_N_m * rho, cf->axial_force_N, 1e-12 * T);
  }
  // Below B / (4 rho^2) the lift-off angle would exceed pi: no arc.
  EXPECT_FALSE(rod_wrapped_on_cylinder(B, 0.99 * B / (4 * rho * rho), rho).has_value());
  EXPECT_TRUE(rod_wrapped_on_cylinder(B, 1.01 * B / (4 * rho * rho), rho).has_value());
}

TEST(ContactClosedForm, RefusesOutsideTheDomain) {
  EXPECT_THROW(heavy_rod_on_floor(1.0, 1.0, 0.0), DomainError);
  EXPECT_THROW(heavy_rod_on_floor(-1.0, 1.0, 1.0), DomainError);
  EXPECT_THROW(cantilever_on_cylinder(1.0, 1.0, 1.0, -1.0), DomainError);
  EXPECT_THROW(rod_wrapped_on_cylinder(1.0, 1.0, 0.0), DomainError);
}

}  // namespace
}  // namespace tcasim::rod
