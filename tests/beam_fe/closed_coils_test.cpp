// Coil contact in the beam FE solver (docs/conventions.md "Closed coils"): a TCA held closed
// by a load above its blocked force is a rigid strut, the constant-strain closed form that the
// FE reproduces on any mesh (strains, tensions, nodal rotations); above the onset it opens.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "beam_fe/beam_fe.hpp"
#include "common/so3.hpp"
#include "common/units.hpp"
#include "models.hpp"

namespace tcasim::beam_fe {
namespace {

using testing::options;
using testing::run;
using testing::Solved;

/// Converged Newton (tolerance_rel 1e-12): the constant-strain closed form to round-off.
constexpr double kExact = 1e-10;

TEST(BeamFeClosedCoils, TcaHeldClosedByALoadAboveItsBlockedForceIsARigidStrutOnAnyMesh) {
  const double t_K = units::degC_to_K(25.0);
  const rod::RodModel m = testing::strut_rod(0.5, t_K);
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const double fb = m.actuators[0].drive.tca->blocked_force(t_K);
  ASSERT_LT(cf.strut_tension_N, fb);
  const Eigen::Vector3d omega(0.0, cf.kappa_1_m, 0.0);
  for (const int order : {1, 2}) {
    for (const int elements : {1, 3, 8}) {
      SCOPED_TRACE(::testing::Message() << "order " << order << ", elements " << elements);
      const Options opt = options(elements, order);
      const Solved s = run(m, opt);
      ASSERT_TRUE(s.summary.converged()) << s.summary.message;
      const rod::Result r = make_result(m, opt, s.state, s.summary);
      EXPECT_NEAR(r.actuators[0].tension_N, cf.strut_tension_N,
                  kExact * std::abs(cf.strut_tension_N));
      EXPECT_LE(std::abs(r.actuators[0].elongation_m), kExact * m.length_m);
      EXPECT_TRUE(r.actuators[0].coils_closed);
      EXPECT_NEAR(r.actuators[0].contact_force_N, fb - cf.strut_tension_N,
                  kExact * std::abs(cf.strut_tension_N));
      for (std::size_t k = 0; k < s.state.s_m.size(); ++k) {
        const Eigen::Matrix3d R_exact = so3::exp(s.state.s_m[k] * omega);
        EXPECT_LT((s.state.q_WB[k].toRotationMatrix() - R_exact).cwiseAbs().maxCoeff(), kExact);
      }
      for (const PointStrain& p : Discretization(m, opt).strains(s.state)) {
        EXPECT_NEAR(p.nu_B.z(), cf.nu3, kExact);
        EXPECT_NEAR(p.omega_B.y(), cf.kappa_1_m, kExact * std::abs(cf.kappa_1_m));
      }
    }
  }
}

TEST(BeamFeClosedCoils, OpenCoilTcaHeldAtItsClosedLengthNd0IsARigidStrut) {
  // A measured fiber: the coils touch at n d0 < L, delta_c = n d0 - L; the strut holds there.
  const double t_K = units::degC_to_K(25.0);
  const rod::RodModel m = testing::open_coil_strut_rod(0.5, t_K);
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const tca::Tca& tca = *m.actuators[0].drive.tca;
  const double dc = tca.closed_elongation_m(), fc = tca.closed_force(t_K);
  ASSERT_LT(dc, 0.0);
  ASSERT_LT(cf.strut_tension_N, fc);
  for (const int order : {1, 2}) {
    SCOPED_TRACE(::testing::Message() << "order " << order);
    const Options opt = options(4, order);
    const Solved s = run(m, opt);
    ASSERT_TRUE(s.summary.converged()) << s.summary.message;
    const rod::Result r = make_result(m, opt, s.state, s.summary);
    EXPECT_NEAR(r.actuators[0].tension_N, cf.strut_tension_N,
                kExact * std::abs(cf.strut_tension_N));
    EXPECT_NEAR(r.actuators[0].elongation_m, dc, kExact * m.length_m);
    EXPECT_TRUE(r.actuators[0].coils_closed);
    EXPECT_NEAR(r.actuators[0].contact_force_N, fc - cf.strut_tension_N,
                kExact * std::abs(cf.strut_tension_N));
  }
}

TEST(BeamFeClosedCoils, HeatedAboveTheOnsetTheCoilsOpenAndTheTcaPushes) {
  const double t_K = units::degC_to_K(25.0);
  rod::RodModel m = testing::strut_rod(0.05, t_K);
  const testing::StrutClosedForm cf = testing::strut_closed_form(m);
  const tca::Tca& tca = *m.actuators[0].drive.tca;
  const std::optional<double> onset =
      tca.onset_temperature(cf.strut_tension_N, t_K, units::degC_to_K(160.0));
  ASSERT_TRUE(onset.has_value());
  m.actuators[0].drive.segments[0].temperature_K = *onset + 20.0;
  const Options opt = options(8, 2);
  const Solved s = run(m, opt);
  ASSERT_TRUE(s.summary.converged()) << s.summary.message;
  const rod::Result r = make_result(m, opt, s.state, s.summary);
  EXPECT_FALSE(r.actuators[0].coils_closed);
  EXPECT_EQ(r.actuators[0].contact_force_N, 0.0);
  EXPECT_GT(r.actuators[0].elongation_m, 0.0);
  EXPECT_LT(r.actuators[0].tension_N, cf.strut_tension_N);  // pushes harder than the strut did
  std::printf("[fe onset] onset %.4f degC; at +20 K: T = %.5e N, delta = %.3e m\n",
              units::K_to_degC(*onset), r.actuators[0].tension_N, r.actuators[0].elongation_m);
}

}  // namespace
}  // namespace tcasim::beam_fe
