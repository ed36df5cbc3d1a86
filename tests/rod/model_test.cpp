// Section geometry, routing derivatives and stiffness helpers of rod::RodModel.
#include "rod/model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"

namespace tcasim::rod {
namespace {

/// Closed-form geometry evaluated in double precision.
constexpr double kRoundOff = 1e-14;
/// Central differences of the helix (angular rate w = 2 pi |k|) have truncation error
/// h^2 w^2/6 and round-off ~eps/(h w) relative to the derivative; with h = 1e-6 m and
/// w ~ 107 rad/m these are 1.9e-9 and 2e-12, so 1e-8 bounds both.
constexpr double kFdStep_m = 1e-6;
constexpr double kFdRelative = 1e-8;

Section rectangle(double w, double h) {
  Section s;
  s.shape = Section::Shape::kRectangle;
  s.width_profile = Profile(w);
  s.height_profile = Profile(h);
  return s;
}

TEST(Section, CircleHalfExtentIsRadiusInEveryDirection) {
  Section s;
  s.shape = Section::Shape::kCircle;
  s.width_profile = Profile(0.008);
  s.height_profile = Profile(0.008);
  for (double a = 0.0; a < 2.0 * units::kPi; a += 0.3) {
    EXPECT_NEAR(s.half_extent_m(std::cos(a), std::sin(a)), 0.004, kRoundOff);
  }
  // The direction need not be unit.
  EXPECT_NEAR(s.half_extent_m(3.0, -4.0), 0.004, kRoundOff);
}

TEST(Section, RectangleHalfExtentReachesTheFirstEdgeAlongTheDirection) {
  const Section s = rectangle(0.010, 0.004);
  EXPECT_NEAR(s.half_extent_m(1.0, 0.0), 0.005, kRoundOff);
  EXPECT_NEAR(s.half_extent_m(-1.0, 0.0), 0.005, kRoundOff);
  EXPECT_NEAR(s.half_extent_m(0.0, 1.0), 0.002, kRoundOff);
  EXPECT_NEAR(s.half_extent_m(0.0, -2.0), 0.002, kRoundOff);
  // Toward the corner (5, 2) mm the distance is the corner's.
  EXPECT_NEAR(s.half_extent_m(0.005, 0.002), std::hypot(0.005, 0.002), kRoundOff);
  // At 45 degrees the top edge y = 2 mm is met first: distance 2 mm * sqrt(2).
  EXPECT_NEAR(s.half_extent_m(1.0, 1.0), 0.002 * std::sqrt(2.0), kRoundOff);
  // Shallow direction: the side edge x = 5 mm is met first.
  const double a = 0.1;
  EXPECT_NEAR(s.half_extent_m(std::cos(a), std::sin(a)), 0.005 / std::cos(a), kRoundOff);
}

TEST(Section, CustomSectionAndZeroDirectionHaveNoHalfExtent) {
  Section custom;
  custom.shape = Section::Shape::kCustom;
  EXPECT_THROW(custom.half_extent_m(1.0, 0.0), DomainError);
  EXPECT_THROW(rectangle(0.01, 0.01).half_extent_m(0.0, 0.0), DomainError);
}

TEST(Routing, StraightRoutingIsAConstantOffset) {
  Routing r;
  r.offset_m = {0.003, -0.001};
  EXPECT_EQ(r.r(0.0), Eigen::Vector3d(0.003, -0.001, 0.0));
  EXPECT_EQ(r.r(0.037), Eigen::Vector3d(0.003, -0.001, 0.0));
  EXPECT_EQ(r.dr(0.01), Eigen::Vector3d::Zero());
  EXPECT_EQ(r.ddr(0.01), Eigen::Vector3d::Zero());
}

TEST(Routing, HelixStartsAtItsPhaseAndKeepsItsRadius) {
  Routing r;
  r.type = Routing::Type::kHelix;
  r.radius_m = 0.003;
  r.phase_rad = units::kPi / 2.0;
  r.turns_per_m = 25.0;
  EXPECT_NEAR((r.r(0.0) - Eigen::Vector3d(0.0, 0.003, 0.0)).norm(), 0.0, kRoundOff);
  // One full turn after 1/k metres.
  EXPECT_NEAR((r.r(1.0 / 25.0) - r.r(0.0)).norm(), 0.0, kRoundOff);
  // A quarter turn later the offset points along -x.
  EXPECT_NEAR((r.r(0.25 / 25.0) - Eigen::Vector3d(-0.003, 0.0, 0.0)).norm(), 0.0, kRoundOff);
  for (double s = 0.0; s < 0.04; s += 0.0037) EXPECT_NEAR(r.r(s).norm(), 0.003, kRoundOff);
}

TEST(Routing, HelixDerivativesMatchCentralFiniteDifferences) {
  Routing r;
  r.type = Routing::Type::kHelix;
  r.radius_m = 0.003;
  r.phase_rad = 0.4;
  r.turns_per_m = -17.0;  // left-handed
  const double w = 2.0 * units::kPi * 17.0;
  for (double s = 0.0; s <= 0.04; s += 0.0053) {
    const Eigen::Vector3d fd1 = (r.r(s + kFdStep_m) - r.r(s - kFdStep_m)) / (2.0 * kFdStep_m);
    const Eigen::Vector3d fd2 = (r.dr(s + kFdStep_m) - r.dr(s - kFdStep_m)) / (2.0 * kFdStep_m);
    EXPECT_LE((r.dr(s) - fd1).norm(), kFdRelative * r.radius_m * w) << "s = " << s;
    EXPECT_LE((r.ddr(s) - fd2).norm(), kFdRelative * r.radius_m * w * w) << "s = " << s;
    EXPECT_EQ(r.dr(s).z(), 0.0);
  }
}

TEST(RodModel, StiffnessesAreDiagonalSectionTimesModulus) {
  RodModel m;
  m.section.shape = Section::Shape::kCustom;
  m.section.area_profile = Profile(2.0);
  m.section.I_x_profile = Profile(3.0);
  m.section.I_y_profile = Profile(5.0);
  m.section.J_profile = Profile(7.0);
  m.material.youngs_modulus_profile = Profile(11.0);
  m.material.poisson_ratio = 0.375;  // G = 11 / 2.75 = 4, exact in binary
  EXPECT_EQ(m.material.shear_modulus(11.0), 4.0);
  EXPECT_EQ(m.shear_extension_stiffness(), Eigen::Vector3d(8.0, 8.0, 22.0));
  EXPECT_EQ(m.bending_torsion_stiffness(), Eigen::Vector3d(33.0, 55.0, 28.0));
}

TEST(RodModel, ConstantProfilesGiveTheSameNumbersAtEverySAsAtTheBase) {
  RodModel m;
  m.length_m = 0.2;
  m.section.shape = Section::Shape::kRectangle;
  m.section.saint_venant_torsion = true;
  m.section.width_profile = Profile(0.01);
  m.section.height_profile = Profile(0.004);
  m.material.youngs_modulus_profile = Profile(1e6);
  m.material.poisson_ratio = 0.3;
  m.material.density_profile = Profile(1100.0);
  m.set_reference_curvature({0.5, -0.25, 0.0});
  ASSERT_TRUE(m.uniform_body());
  const SectionStiffness K0 = m.stiffness_at(0.0);
  const SectionProperties p0 = m.section.properties_at(0.0);
  const double G = 1e6 / (2.0 * (1.0 + 0.3));
  EXPECT_EQ(K0.shear_extension, Eigen::Vector3d(G * p0.area_m2, G * p0.area_m2, 1e6 * p0.area_m2));
  EXPECT_EQ(K0.bending_torsion, Eigen::Vector3d(1e6 * p0.I_x_m4, 1e6 * p0.I_y_m4, G * p0.J_m4));
  for (const double s : {0.05, 0.1, 0.2}) {
    for (const Side side : {Side::kLeft, Side::kRight}) {
      EXPECT_EQ(m.shear_extension_stiffness(s, side), K0.shear_extension);
      EXPECT_EQ(m.bending_torsion_stiffness(s, side), K0.bending_torsion);
      EXPECT_EQ(m.mass_per_length_kg_m(s, side), 1100.0 * p0.area_m2);
      EXPECT_EQ(m.reference_curvature_at(s, side), Eigen::Vector3d(0.5, -0.25, 0.0));
    }
  }
}

TEST(RodModel, WeightPerLengthIsDensityTimesAreaTimesWorldGravity) {
  RodModel m;
  m.section.shape = Section::Shape::kCustom;
  m.section.area_profile = Profile(1e-4);
  m.material.density_profile = Profile(1000.0);
  m.gravity_W_m_s2 = {0.0, -3.0, -9.81};
  // The body frame plays no role: gravity is a world-frame density.
  m.R_WB0 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const Eigen::Vector3d w = m.weight_per_length_W_N_m();
  EXPECT_NEAR((w - Eigen::Vector3d(0.0, -0.3, -0.981)).norm(), 0.0, kRoundOff);
}

}  // namespace
}  // namespace tcasim::rod
