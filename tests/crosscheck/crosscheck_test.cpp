// Tests of the shared cross-check / convergence logic (crosscheck/crosscheck.hpp).
#include "crosscheck/crosscheck.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/error.hpp"
#include "common/so3.hpp"
#include "support/rod_models.hpp"

namespace tcasim::crosscheck {
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

rod::Result make_result(const Eigen::Vector3d& tip, const Eigen::Matrix3d& R,
                        std::vector<double> tensions, std::vector<double> elongations = {}) {
  rod::Result r;
  r.tip_position_W_m = tip;
  r.tip_R_WB = R;
  elongations.resize(tensions.size(), 0.0);
  for (std::size_t i = 0; i < tensions.size(); ++i)
    r.actuators.push_back({"a", tensions[i], elongations[i]});
  r.centerline_s_m = {0.0, 0.02, 0.04};
  r.centerline_p_W_m = {Eigen::Vector3d::Zero(), 0.5 * tip, tip};
  return r;
}

TEST(Difference, MeasuresTipDistanceRotationAngleAndLargestTensionAndElongationGaps) {
  const double angle = 1e-9;  // small: acos of the trace would lose it
  const rod::Result a =
      make_result({0, 0, 0.04}, Eigen::Matrix3d::Identity(), {1.0, -2.0}, {1e-3, -2e-3});
  const rod::Result b = make_result({3e-6, 4e-6, 0.04}, so3::exp(Eigen::Vector3d(0.0, angle, 0.0)),
                                    {1.5, -2.25}, {0.5e-3, -2.75e-3});
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

TEST(AsymptoticRange, EndsWhereTheErrorStopsFallingAtTheFloor) {
  // Order 4 down to a floor of 1e-9: the two floor levels are excluded.
  const std::vector<double> h = {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64, 1.0 / 128, 1.0 / 256};
  const std::vector<double> e = {1.6e-5, 1.0e-6, 6.25e-8, 3.9e-9, 2.1e-9, 3.0e-9};
  EXPECT_EQ(asymptotic_level_count(h, e, order_bracket(2), std::vector<double>(6, 1e-8)), 4);
  // The same data with a floor estimate far below: the low orders are not round-off.
  EXPECT_EQ(asymptotic_level_count(h, e, order_bracket(2), std::vector<double>(6, 1e-12)), 6);
  // A clean power law has no floor, whatever the estimate.
  std::vector<double> clean;
  for (double hi : h) clean.push_back(std::pow(hi, 4.0));
  EXPECT_EQ(asymptotic_level_count(h, clean, order_bracket(2), std::vector<double>(6, 1.0)), 6);
  // A zero error (an exact level) counts as refinement that stopped helping.
  EXPECT_EQ(asymptotic_level_count({0.5, 0.25, 0.125}, {1e-3, 6e-5, 0.0}, order_bracket(2),
                                   {1e-6, 1e-6, 1e-6}),
            2);
  EXPECT_THROW(asymptotic_level_count(h, e, order_bracket(2), {1e-8}), std::invalid_argument);
}

TEST(AsymptoticRange, FloorEstimateGrowsWithTheStiffnessRatioAndTheNodes) {
  rod::RodModel m;
  m.length_m = 2.0;
  m.section.shape = rod::Section::Shape::kCustom;
  m.material.youngs_modulus_profile = rod::Profile(1.0);
  m.material.poisson_ratio = 0.0;               // G = 0.5
  m.section.area_profile = rod::Profile(4e12);  // EA; GA = 2e12
  m.section.I_x_profile = rod::Profile(4.0);
  m.section.I_y_profile = rod::Profile(8.0);
  m.section.J_profile = rod::Profile(1.0);
  // eps nodes max(EA, GA) L^2 / min(EI) L = eps 9 4e12 4 / 4 2 (4 quadratic elements).
  EXPECT_NEAR(fe_round_off_floor_m(m, 2, 4), 2.220446049250313e-16 * 9 * 8e12, kRoundOff * 1.6e-2);
}

/// Quadratic elements on Mattiasson's cantilever (k = 5) with EA L^2 / EI = 1e8, 4 to 256
/// elements: the error falls at order 4 (measured 3.95 to 4.00) down to 2.1e-9 L at 64
/// elements, then jumps to the round-off floor (1.9e-6 L at 128, estimate 5.7e-6 L).
constexpr double kStiffRatio = 1e8;
constexpr double kStiffLoad = 5.0;
/// The floor estimate is an upper estimate: errors at the floor stay below it.
constexpr double kFloorEstimateFactor = 1.0;

TEST(AsymptoticRange, StiffCantileverStudyReportsTheFloorInsteadOfAReversedOrder) {
  rod::RodModel m = test_support::custom_rod(1.0, kStiffRatio, kStiffRatio, 1.0, 1.0);
  m.name = "stiff-cantilever";
  m.tip_force_W_N = Eigen::Vector3d(kStiffLoad, 0.0, 0.0);
  ReferenceSettings rs;
  rs.steps = 512;
  rs.cvode_rtol = 0.0;
  const Reference ref = shooting_reference(m, rs);
  ASSERT_TRUE(ref.converged());
  FeSettings tol = tight_tolerances();
  tol.order = 2;
  const ConvergenceStudy study = convergence_study(m, ref, tol, refinement_levels(4, 7));
  const std::string table = convergence_table(study);
  std::printf("%s", table.c_str());
  ASSERT_TRUE(study.converged());
  const OrderBracket b = order_bracket(2);
  EXPECT_GE(study.asymptotic_levels, 3) << table;
  EXPECT_LT(study.asymptotic_levels, static_cast<int>(study.levels.size())) << table;
  for (int i = 1; i < study.asymptotic_levels; ++i) {
    EXPECT_TRUE(b.contains(study.levels[i].observed_order)) << "level " << i << "\n" << table;
  }
  EXPECT_TRUE(b.contains(study.asymptotic_order)) << table;
  for (std::size_t i = study.asymptotic_levels; i < study.levels.size(); ++i) {
    EXPECT_TRUE(study.levels[i].round_off) << table;
    EXPECT_LE(study.levels[i].error_m, kFloorEstimateFactor * study.levels[i].floor_estimate_m)
        << table;
  }
  EXPECT_NE(table.find("round-off floor"), std::string::npos) << table;
  const std::string csv = convergence_csv_rows(m.name, study);
  EXPECT_NE(csv.find(",round-off floor,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",asymptotic,"), std::string::npos) << csv;
}

}  // namespace
}  // namespace tcasim::crosscheck
