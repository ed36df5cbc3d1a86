// The dynamic cross-check (crosscheck/dynamic.hpp) on a body whose Kelvin-Voigt viscosity
// varies along s: both methods take the model's profile.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "crosscheck/dynamic.hpp"
#include "rod/scenario.hpp"

namespace tcasim::crosscheck {
namespace {

using json = nlohmann::json;

/// The tip pulse of the dynamic suite with body.material.viscosity_Pa_s = `viscosity`.
rod::RodModel pulse_with_viscosity(const json& viscosity) {
  std::ifstream in(std::filesystem::path(TCASIM_SOURCE_DIR) / "validation" / "scenarios" /
                   "dynamic" / "steel-tip-pulse.json");
  json doc = json::parse(in);
  doc["body"]["material"]["viscosity_Pa_s"] = viscosity;
  return rod::parse_scenario(doc);
}

DynamicSettings short_run() {
  DynamicSettings s;
  s.duration_s = 0.02;
  s.dt_s = 1e-3;
  s.steps = 40;
  s.elements = 8;
  return s;
}

// A viscosity profile reaches the FE run (it was refused with a DomainError before): the FE
// takes it, the result differs from the undamped and from the uniformly damped run, and the
// two methods stay close (both damp the same profile).
TEST(DynamicCrosscheck, BothMethodsTakeAViscosityProfileAlongS) {
  const json profile = {{"s_m", {0.0, 0.5}}, {"values", {4e9, 0.0}}};
  const rod::RodModel varying = pulse_with_viscosity(profile);
  ASSERT_FALSE(varying.material.viscosity_profile.is_constant());
  EXPECT_EQ(fe_dynamics_unsupported(varying), "");
  const DynamicSettings s = short_run();
  const DynamicRun fe = run_dynamics(varying, DynamicMethod::kFe, s);
  const DynamicRun sh = run_dynamics(varying, DynamicMethod::kShooting, s);
  ASSERT_TRUE(fe.ok) << fe.message;
  ASSERT_TRUE(sh.ok) << sh.message;
  const DynamicRun fe_undamped = run_dynamics(pulse_with_viscosity(0.0), DynamicMethod::kFe, s);
  const DynamicRun fe_uniform = run_dynamics(pulse_with_viscosity(4e9), DynamicMethod::kFe, s);
  ASSERT_TRUE(fe_undamped.ok && fe_uniform.ok);
  const double between = trajectory_difference(fe, sh).max_m;
  EXPECT_GT(trajectory_difference(fe, fe_undamped).max_m, 10.0 * between);
  EXPECT_GT(trajectory_difference(fe, fe_uniform).max_m, 10.0 * between);
}

}  // namespace
}  // namespace tcasim::crosscheck
