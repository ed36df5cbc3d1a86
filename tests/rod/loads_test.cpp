// rod::Loads: the loads of the model file, setters, the load scale and validation.
#include "rod/loads.hpp"

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "common/units.hpp"
#include "support/rod_models.hpp"

namespace tcasim::rod {
namespace {

RodModel two_actuator_model() {
  RodModel m = test_support::circular_manipulator(units::degC_to_K(60.0));
  test_support::add_tension_string(m, "pull", -0.002, 0.002, 0.25);
  m.tip_force_W_N = {0.0, 1e-3, 0.0};
  m.tip_moment_W_Nm = {2e-5, 0.0, 0.0};
  return m;
}

TEST(Loads, FromModelCopiesTheModelsOwnLoads) {
  const RodModel m = two_actuator_model();
  const Loads l = Loads::from_model(m);
  ASSERT_EQ(l.actuators.size(), 2u);
  EXPECT_EQ(l.actuators[0].segments.size(), m.actuators[0].drive.segments.size());
  EXPECT_EQ(l.actuators[0].segments[0].temperature_K, units::degC_to_K(60.0));
  EXPECT_EQ(l.actuators[1].tension_N, 0.25);
  EXPECT_EQ(l.tip_force_W_N, m.tip_force_W_N);
  EXPECT_EQ(l.tip_moment_W_Nm, m.tip_moment_W_Nm);
  EXPECT_EQ(l.gravity_W_m_s2, m.gravity_W_m_s2);
  EXPECT_EQ(l.load_scale, 1.0);
  EXPECT_NO_THROW(l.validate(m));
}

TEST(Loads, SettersChangeOneActuatorAndRejectABadIndex) {
  const RodModel m = two_actuator_model();
  Loads l = Loads::from_model(m);
  l.set_temperature_K(0, 350.0);
  EXPECT_EQ(l.actuators[0].segments[0].temperature_K, 350.0);
  l.set_segment_temperatures_K(0, {360.0});
  EXPECT_EQ(l.actuators[0].segments[0].temperature_K, 360.0);
  EXPECT_THROW(l.set_segment_temperatures_K(0, {360.0, 370.0}), InputError);
  l.set_tension_N(1, 0.5);
  EXPECT_EQ(l.actuators[1].tension_N, 0.5);
  EXPECT_THROW(l.set_tension_N(2, 0.5), InputError);
  EXPECT_THROW(l.set_temperature_K(5, 300.0), InputError);
}

TEST(Loads, AppliedScalesForcesAndRampsTemperaturesFromTheReference) {
  const RodModel m = two_actuator_model();
  Loads l = Loads::from_model(m);
  EXPECT_EQ(l.applied(m).actuators[0].segments[0].temperature_K,
            l.actuators[0].segments[0].temperature_K);
  l.load_scale = 0.25;
  const Loads a = l.applied(m);
  EXPECT_EQ(a.load_scale, 1.0);
  EXPECT_EQ(a.actuators[1].tension_N, 0.25 * 0.25);
  EXPECT_EQ(a.tip_force_W_N, 0.25 * m.tip_force_W_N);
  EXPECT_EQ(a.tip_moment_W_Nm, 0.25 * m.tip_moment_W_Nm);
  EXPECT_EQ(a.gravity_W_m_s2, 0.25 * m.gravity_W_m_s2);
  const double t_ref = m.actuators[0].drive.tca->material().reference_temperature_K;
  EXPECT_DOUBLE_EQ(a.actuators[0].segments[0].temperature_K,
                   t_ref + 0.25 * (units::degC_to_K(60.0) - t_ref));
}

TEST(Loads, ValidateNamesTheFieldThatDoesNotFitTheModel) {
  const RodModel m = two_actuator_model();
  Loads l = Loads::from_model(m);
  l.actuators[0].segments.clear();
  try {
    l.validate(m);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "loads.actuators[0].segments");
  }
  l = Loads::from_model(m);
  l.load_scale = -0.1;
  EXPECT_THROW(l.validate(m), InputError);
  l = Loads::from_model(m);
  l.actuators.resize(3);
  EXPECT_THROW(l.validate(m), InputError);
}

TEST(Loads, CharacteristicForceIsTheLargerOfTheBendingScaleAndTheLargestLoad) {
  RodModel m = two_actuator_model();
  const double L = m.length_m;
  const double EI = m.bending_torsion_stiffness().head<2>().minCoeff();
  Loads l = Loads::from_model(m);
  l.tip_force_W_N.setZero();
  l.tip_moment_W_Nm.setZero();
  l.gravity_W_m_s2.setZero();
  l.set_tension_N(1, 0.0);
  EXPECT_EQ(characteristic_force_N(m, l), EI / (L * L));
  l.set_tension_N(1, -5.0);  // c |T| of a tension drive (the TCA's tension is an unknown)
  EXPECT_EQ(characteristic_force_N(m, l), 5.0);
  l.tip_moment_W_Nm = {0.0, 0.0, 7.0 * L};
  EXPECT_DOUBLE_EQ(characteristic_force_N(m, l), 7.0);
  l.tip_force_W_N = {0.0, 8.0, 0.0};
  EXPECT_EQ(characteristic_force_N(m, l), 8.0);
  l.load_scale = 0.5;  // of the applied loads
  EXPECT_DOUBLE_EQ(characteristic_force_N(m, l), 4.0);
  l = Loads::from_model(m);
  l.gravity_W_m_s2 = {0.0, 0.0, -1e6};
  EXPECT_DOUBLE_EQ(characteristic_force_N(m, l), m.mass_per_length_kg_m(0.0) * 1e6 * L);
}

}  // namespace
}  // namespace tcasim::rod
