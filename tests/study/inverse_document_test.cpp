// Tests of the inverse and grasp documents (study/inverse_document.hpp) that `tcasim
// inverse/grasp` write and tcasim.inverse/grasp return: the numbers of the library solves they
// wrap, in the documented fields.
#include "study/inverse_document.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/units.hpp"
#include "cosserat/shooting.hpp"
#include "rod/scenario.hpp"

namespace tcasim::study {
namespace {

const std::string kScenarios = std::string(TCASIM_SOURCE_DIR) + "/validation/scenarios/";

TEST(InverseDocument, HoldsTheSolveInverseResultFromRest) {
  const rod::RodModel model = rod::read_scenario(kScenarios + "square-manipulator-25C.json");
  const Eigen::Vector3d target(-1.962027285920e-03, 0.0, 3.992439219707e-02);
  cosserat::InverseOptions o;
  o.actuators = {0};
  const DocumentRun run = inverse_document(model, target, o);

  // The same solve by hand: default options, the TCA at its material's reference temperature.
  cosserat::ShootingSolver solver(model, cosserat::Options{});
  rod::Loads act = rod::Loads::from_model(model);
  act.set_temperature_K(0, model.actuators[0].drive.tca->material().reference_temperature_K);
  cosserat::Solution sol;
  const cosserat::InverseResult r = cosserat::solve_inverse(solver, model, target, o, act, sol);

  const nlohmann::json& j = run.document;
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_TRUE(run.converged);
  EXPECT_EQ(run.status, cosserat::to_string(r.status));
  EXPECT_EQ(j["schema"], "tcasim.inverse/1");
  EXPECT_EQ(j["scenario"], model.name);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["status"], run.status);
  EXPECT_EQ(j["iterations"], r.iterations);
  EXPECT_EQ(j["forward_solves"], r.forward_solves);
  EXPECT_EQ(j["distance_m"].get<double>(), r.distance_m);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(j["target_m"][k].get<double>(), target[k]);
    EXPECT_EQ(j["tip"]["position_m"][k].get<double>(), r.tip_position_W_m[k]);
  }
  ASSERT_EQ(j["actuators"].size(), 1u);
  const nlohmann::json& a = j["actuators"][0];
  EXPECT_EQ(a["name"], model.actuators[0].name);
  EXPECT_EQ(a["temperature_degC"].get<double>(), units::K_to_degC(r.values[0]));
  EXPECT_EQ(a["at_bound"], false);
  EXPECT_EQ(a["coils_closed"], false);
  EXPECT_EQ(a["contact_force_N"].get<double>(), 0.0);
}

TEST(InverseDocument, AnUnreachableTargetIsAWrittenDocumentNotConverged) {
  const rod::RodModel model = rod::read_scenario(kScenarios + "square-manipulator-25C.json");
  const DocumentRun run = inverse_document(model, Eigen::Vector3d(0.05, 0.0, 0.0), {});
  EXPECT_FALSE(run.converged);
  EXPECT_EQ(run.status, "unreachable");
  EXPECT_EQ(run.document["converged"], false);
  EXPECT_EQ(run.document["message"], run.message);
  EXPECT_GT(run.document["distance_m"].get<double>(), 1e-3);
}

TEST(GraspDocument, RepeatsTheInputsAndHoldsTheSolveGraspResult) {
  const rod::RodModel model = rod::read_scenario(kScenarios + "gripper-finger.json");
  const DocumentRun run = grasp_document(model, 10.0, 0.5, 2, std::nan(""));
  cosserat::GraspOptions o;
  o.mass_kg = 0.010;
  o.friction = 0.5;
  o.fingers = 2;
  cosserat::Options so;
  so.tolerance = 1e-12;
  const cosserat::GraspResult r = cosserat::solve_grasp(model, so, o);
  const nlohmann::json& j = run.document;
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_TRUE(run.converged);
  EXPECT_EQ(run.status, "converged");
  EXPECT_EQ(j["schema"], "tcasim.grasp/1");
  EXPECT_EQ(j["mass_g"].get<double>(), 10.0);
  EXPECT_EQ(j["friction"].get<double>(), 0.5);
  EXPECT_EQ(j["fingers"], 2);
  EXPECT_EQ(j["temperature_degC"].get<double>(), units::K_to_degC(r.temperature_K));
  EXPECT_EQ(j["normal_force_N"].get<double>(), r.required_force_N);
  EXPECT_EQ(j["blocked_normal_force_N"].get<double>(), r.blocked_normal_force_N);
  EXPECT_EQ(j["iterations"], r.iterations);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(j["tip"]["position_m"][k].get<double>(), r.tip_position_W_m[k]);
}

}  // namespace
}  // namespace tcasim::study
