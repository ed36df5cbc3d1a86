// Tests of the shared cross-check / convergence logic (validation/common/crosscheck.hpp).
#include "validation/common/crosscheck.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/error.hpp"
#include "common/so3.hpp"

namespace tcasim::validation {
namespace {

/// Closed-form inputs evaluated in double precision: only round-off remains.
constexpr double kRoundOff = 1e-12;

TEST(ObservedOrders, RecoverTheExponentOfAPowerLawForAnyRatio) {
  const std::vector<double> h = {0.1, 0.05, 0.02, 0.01};
  std::vector<double> e;
  for (double x : h) e.push_back(3.0 * std::pow(x, 4));
  for (double p : observed_orders(h, e)) EXPECT_NEAR(p, 4.0, kRoundOff);
}

TEST(ObservedOrders, ZeroErrorGivesNaNAndBadInputThrows) {
  const auto p = observed_orders({0.1, 0.05}, {1e-3, 0.0});
  EXPECT_TRUE(std::isnan(p[0]));
  EXPECT_THROW(observed_orders({0.1}, {1.0}), std::invalid_argument);
  EXPECT_THROW(observed_orders({0.1, 0.1}, {1.0, 0.5}), std::invalid_argument);
  EXPECT_THROW(observed_orders({0.1, 0.05}, {1.0}), std::invalid_argument);
}

TEST(Richardson, ExtrapolatesAnExactPowerLawToItsLimitAndOrder) {
  const Eigen::Vector3d limit(0.01, -0.02, 0.04);
  const Eigen::Vector3d c(1.0, 2.0, -0.5);
  const std::vector<double> h = {0.02, 0.01, 0.005};
  std::vector<Eigen::Vector3d> u;
  for (double x : h) u.push_back(limit + c * std::pow(x, 2));
  const Richardson r = richardson(h, u);
  EXPECT_NEAR(r.order, 2.0, 1e-9);
  EXPECT_LT((r.value - limit).norm(), kRoundOff);
}

TEST(Richardson, RejectsUnequalRatiosAndWrongOrdering) {
  const std::vector<Eigen::Vector3d> u(3, Eigen::Vector3d::Zero());
  EXPECT_THROW(richardson({0.04, 0.02, 0.005}, u), std::invalid_argument);
  EXPECT_THROW(richardson({0.01, 0.02, 0.04}, u), std::invalid_argument);
}

TEST(Richardson, IdenticalLevelsGiveNoOrder) {
  const std::vector<Eigen::Vector3d> u(3, Eigen::Vector3d(1.0, 2.0, 3.0));
  const Richardson r = richardson({0.04, 0.02, 0.01}, u);
  EXPECT_TRUE(std::isnan(r.order));
  EXPECT_EQ(r.value, u[2]);
}

rod::Result make_result(const Eigen::Vector3d& tip, const Eigen::Matrix3d& R, std::vector<double> tensions,
                        std::vector<double> elongations = {}) {
  rod::Result r;
  r.tip_position_W_m = tip;
  r.tip_R_WB = R;
  elongations.resize(tensions.size(), 0.0);
  for (std::size_t i = 0; i < tensions.size(); ++i) r.actuators.push_back({"a", tensions[i], elongations[i]});
  r.centerline_s_m = {0.0, 0.02, 0.04};
  r.centerline_p_W_m = {Eigen::Vector3d::Zero(), 0.5 * tip, tip};
  return r;
}

TEST(Difference, MeasuresTipDistanceRotationAngleAndLargestTensionAndElongationGaps) {
  const double angle = 1e-9;  // small: acos of the trace would lose it
  const rod::Result a = make_result({0, 0, 0.04}, Eigen::Matrix3d::Identity(), {1.0, -2.0}, {1e-3, -2e-3});
  const rod::Result b =
      make_result({3e-6, 4e-6, 0.04}, so3::exp(Eigen::Vector3d(0.0, angle, 0.0)), {1.5, -2.25}, {0.5e-3, -2.75e-3});
  const ResultDifference d = difference(a, b);
  EXPECT_NEAR(d.tip_m, 5e-6, kRoundOff);
  EXPECT_NEAR(d.mid_m, 2.5e-6, kRoundOff);
  EXPECT_NEAR(d.rotation_rad, angle, 1e-20);
  EXPECT_DOUBLE_EQ(d.max_tension_N, 0.5);
  EXPECT_DOUBLE_EQ(d.max_elongation_m, 0.75e-3);
  EXPECT_EQ(d.reaction_N, 0.0);
}

TEST(Difference, RejectsResultsWithDifferentActuatorCounts) {
  const rod::Result a = make_result({0, 0, 0.04}, Eigen::Matrix3d::Identity(), {1.0});
  const rod::Result b = make_result({0, 0, 0.04}, Eigen::Matrix3d::Identity(), {});
  EXPECT_THROW(difference(a, b), std::invalid_argument);
}

TEST(CenterlinePoint, FindsTheSampleAtAnArcLengthOrThrows) {
  const rod::Result r = make_result({0, 0, 0.04}, Eigen::Matrix3d::Identity(), {});
  EXPECT_EQ(centerline_point(r, 0.02), Eigen::Vector3d(0, 0, 0.02));
  EXPECT_THROW(centerline_point(r, 0.01), std::invalid_argument);
}

TEST(MeasuredArcLength, IsTheMiddleOnlyForAPinnedTip) {
  rod::RodModel m;
  m.length_m = 0.04;
  EXPECT_EQ(measured_arc_length(m), 0.04);
  m.tip_constraint = rod::TipConstraint{};
  EXPECT_EQ(measured_arc_length(m), 0.02);
  m.tip_constraint->normal_W = Eigen::Vector3d::UnitX();
  EXPECT_EQ(measured_arc_length(m), 0.04);
}

TEST(OrderBracket, IsTwoSidedAroundTheTheoreticalOrder) {
  EXPECT_TRUE(order_bracket(1).contains(2.1));
  EXPECT_FALSE(order_bracket(1).contains(2.2));
  EXPECT_FALSE(order_bracket(1).contains(1.8));
  EXPECT_TRUE(order_bracket(2).contains(3.75));
  EXPECT_FALSE(order_bracket(2).contains(4.5));
  EXPECT_FALSE(order_bracket(2).contains(std::nan("")));
  EXPECT_THROW(order_bracket(3), std::invalid_argument);
}

TEST(RefinementLevels, DoubleFromTheCoarsest) {
  EXPECT_EQ(refinement_levels(8, 4), (std::vector<int>{8, 16, 32, 64}));
  EXPECT_THROW(refinement_levels(0, 3), InputError);
}

TEST(ScenarioFiles, ListsOnlyScenarioSchemaFilesSortedAndCountsTheExpectedSuite) {
  const auto dir = std::filesystem::temp_directory_path() / "tcasim_crosscheck_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "b.json") << R"({"schema": "tcasim.scenario/1", "name": "b"})";
  std::ofstream(dir / "a.json") << R"({"schema": "tcasim.scenario/1", "name": "a"})";
  std::ofstream(dir / "t.json") << R"({"schema": "tcasim.tcas/1", "name": "t"})";
  std::ofstream(dir / "broken.json") << "{";
  std::ofstream(dir / "notes.txt") << "x";
  const auto files = scenario_files(dir.string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(std::filesystem::path(files[0]).filename(), "a.json");
  EXPECT_EQ(std::filesystem::path(files[1]).filename(), "b.json");
  // The count a suite program must run: the scenario files, the names asked for, or a floor.
  EXPECT_EQ(expected_scenarios(dir.string(), {}, 1), 2u);
  EXPECT_EQ(expected_scenarios(dir.string(), {"a", "b", "missing"}, 1), 3u);
  EXPECT_EQ(expected_scenarios(dir.string(), {}, kShippedSuiteScenarios), kShippedSuiteScenarios);
  std::filesystem::remove_all(dir);
  EXPECT_THROW(scenario_files(dir.string()), InputError);
}

TEST(StudyLevels, QuickUsesFewerLevelsThanFullFromTheSameCoarsestMesh) {
  for (int order : {1, 2}) {
    const StudyLevels q = study_levels("circular-manipulator", order, true);
    const StudyLevels f = study_levels("circular-manipulator", order, false);
    EXPECT_GE(q.count, 3);
    EXPECT_LT(q.count, f.count);
    EXPECT_EQ(q.coarsest, f.coarsest);
  }
}

}  // namespace
}  // namespace tcasim::validation
