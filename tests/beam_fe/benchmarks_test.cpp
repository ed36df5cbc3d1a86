// Bathe-Bolourchi 45-degree bend: a precurved cantilever (R = 100, 1 x 1 section,
// E = 1e7, nu = 0, so G = E/2; I = 1/12) under a tip load out of its plane, against the
// tip positions of Simo & Vu-Quoc [Simo1986] (8 elements). The torsion constant is stated
// explicitly: Saint-Venant for a unit square (J = 0.1406, the gated case), and the polar
// J = 1/6 for comparison (reported only).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "beam_fe/beam_fe.hpp"
#include "common/units.hpp"
#include "models.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Vector3d;

rod::RodModel bend(double J, double P) {
  const double E = 1e7, G = 0.5 * E, R = 100.0;
  rod::RodModel m = testing::stiffness_rod(units::kPi * R / 4.0, E, G, E / 12.0, E / 12.0, G * J);
  m.name = "bathe-bolourchi";
  // Body e3 along world x at the base, e1 along world y (toward the center of curvature at
  // (0, R, 0)), e2 along world z: curvature 1/R about body e2 bends toward body e1.
  m.R_WB0 << 0, 0, 1,  //
      1, 0, 0,         //
      0, 1, 0;
  m.set_reference_curvature({0.0, 1.0 / R, 0.0});
  m.tip_force_W_N = {0.0, 0.0, P};
  return m;
}

struct Reference {
  double P;
  Vector3d tip;
};
/// [Simo1986] tip positions (8 elements).
const Reference kSimoVuQuoc[] = {
    {300.0, {58.84, 22.33, 40.08}}, {450.0, {52.32, 18.62, 48.39}}, {600.0, {47.23, 15.79, 53.37}}};

Vector3d solve_tip(const rod::RodModel& m, int elements, int order) {
  Options opt;
  opt.elements = elements;
  opt.order = order;
  State st;
  const Summary s = solve(m, opt, st);
  EXPECT_TRUE(s.converged()) << s.message;
  return st.p_W_m.back();
}

TEST(BeamFeBenchmarks, BatheBolourchiReferenceGeometryIsTheFortyFiveDegreeArc) {
  const rod::RodModel m = bend(0.1406, 0.0);
  Options opt;
  opt.elements = 8;
  const State st = Discretization(m, opt).reference_state();
  const double c = 100.0 * std::sqrt(0.5);
  EXPECT_NEAR(st.p_W_m.back().x(), c, 1e-12);
  EXPECT_NEAR(st.p_W_m.back().y(), 100.0 - c, 1e-12);
  EXPECT_NEAR(st.p_W_m.back().z(), 0.0, 1e-12);
}

TEST(BeamFeBenchmarks, BatheBolourchiBendMatchesSimoVuQuocWithinTheirOnePercentSpread) {
  // Published codes differ by about 1 % (mostly through J, which the reference does not
  // state): each coordinate of the converged tip must lie within 1 % of the tip's distance
  // from the base, |p_ref|, of the reference value.
  constexpr double kPublishedSpread = 0.01;
  for (const Reference& ref : kSimoVuQuoc) {
    const rod::RodModel m = bend(0.1406, ref.P);
    const Vector3d lin8 = solve_tip(m, 8, 1), quad8 = solve_tip(m, 8, 2),
                   quad64 = solve_tip(m, 64, 2);
    const Vector3d polar = solve_tip(bend(1.0 / 6.0, ref.P), 64, 2);
    std::printf("P = %g: reference (%.2f, %.2f, %.2f)\n", ref.P, ref.tip.x(), ref.tip.y(),
                ref.tip.z());
    auto row = [&](const char* what, const Vector3d& p) {
      const Vector3d d = p - ref.tip;
      std::printf("  %-28s (%.3f, %.3f, %.3f)  diff (%+.3f, %+.3f, %+.3f) = %.2f %% of |p_ref|\n",
                  what, p.x(), p.y(), p.z(), d.x(), d.y(), d.z(),
                  100.0 * d.cwiseAbs().maxCoeff() / ref.tip.norm());
    };
    row("J = 0.1406, 8 linear", lin8);
    row("J = 0.1406, 8 quadratic", quad8);
    row("J = 0.1406, 64 quadratic", quad64);
    row("J = 1/6 (polar), 64 quadratic", polar);
    SCOPED_TRACE(::testing::Message() << "P = " << ref.P);
    EXPECT_LT((quad64 - ref.tip).cwiseAbs().maxCoeff(), kPublishedSpread * ref.tip.norm());
  }
}

}  // namespace
}  // namespace tcasim::beam_fe
