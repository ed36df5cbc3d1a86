#pragma once
/// Cross-checks of the two forward solvers (Cosserat shooting, beam FE) and h-convergence
/// studies of the FE, shared by `tcasim compare`, `tcasim converge` and the validation
/// programs validate_crosscheck and validate_convergence (one implementation).
///
/// Reference: the shooting solver with classical RK4 at a high step count. Its own error
/// is estimated by solving again with half the steps: for a fourth-order method
/// e(N) ~ |p(N) - p(N/2)| / (2^4 - 1) (Richardson). CVODE at a tight tolerance is solved
/// as a second opinion and its distance to the reference reported.
/// Errors are Euclidean norms of the tip-position difference [m] (world frame).
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/convergence.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::crosscheck {

/// Paths of the `tcasim.scenario/1` files in `dir` (other JSON schemas are left out),
/// sorted by file name. Throws InputError if `dir` is not a readable folder.
std::vector<std::string> scenario_files(const std::string& dir);

/// Scenarios of the shipped suite (validation/scenarios): a suite program run on the whole
/// shipped folder must run at least these many, so a lost file fails its count gate instead
/// of shrinking the suite unnoticed.
constexpr std::size_t kShippedSuiteScenarios = 17;

/// How many scenarios a suite program must run (Gates::expect_count): the names in `only`
/// when it is not empty, else the `tcasim.scenario/1` files of `dir`, and at least `minimum`.
std::size_t expected_scenarios(const std::string& dir, const std::vector<std::string>& only,
                               std::size_t minimum);

/// The suite: the scenario files of `dir` (restricted to the names in `only` when it is not
/// empty); both solvers solve every scenario, so `skipped` (name, reason; for the program to
/// report as not run, Gates::not_run) is left as it is.
/// Prints one line per scenario.
std::vector<rod::RodModel> load_suite(const std::string& dir, const std::vector<std::string>& only,
                                      std::vector<std::pair<std::string, std::string>>& skipped);

/// Centerline position at arc length s_m: the result's sample there (within 1e-9 of the
/// spacing scale L); throws std::invalid_argument when no sample lies at s_m.
Eigen::Vector3d centerline_point(const rod::Result& result, double s_m);

/// Arc length whose position a convergence study measures: the tip (L), except when the
/// tip is pinned (a position-holding tip constraint makes the tip error zero by
/// construction): then the middle, L/2.
double measured_arc_length(const rod::RodModel& model);

/// Differences between two results of the same model.
struct ResultDifference {
  double tip_m = 0.0;             ///< |p_a(L) - p_b(L)| [m]
  double mid_m = 0.0;             ///< |p_a(L/2) - p_b(L/2)| [m] (NaN without a sample at L/2)
  double reaction_N = 0.0;        ///< |tip reaction a - b| [N] (0 without a tip constraint)
  double rotation_rad = 0.0;      ///< |log(R_a(L)^T R_b(L))| [rad]
  double max_tension_N = 0.0;     ///< max over actuators of |T_a - T_b| (one string) [N]
  double max_elongation_m = 0.0;  ///< max over actuators of |e_a - e_b| (one string) [m]
  /// max over obstacles of |F_a - F_b| of the contact resultants [N] (0 without obstacles)
  double max_contact_N = 0.0;
  /// |base reaction force a - b| [N] (NaN when either result lacks it)
  double base_force_N = 0.0;
};
/// a - b as above; throws std::invalid_argument if the actuator or obstacle counts differ.
ResultDifference difference(const rod::Result& a, const rod::Result& b);

/// One solve with its outcome and wall time.
struct Run {
  rod::Result result;
  bool converged = false;
  std::string status;   ///< the solver's status name ("converged", ...) or its message
  double time_s = 0.0;  ///< wall time of the solve (without result assembly) [s]
};

/// Shooting solve of the model's own actuation with `steps` equal RK4 steps (even), Newton
/// stopping at a scaled residual of `tolerance` (cosserat::Options::tolerance).
Run solve_shooting_rk4(const rod::RodModel& model, int steps, double tolerance);
/// Shooting solve with SUNDIALS CVODE at relative tolerance `rtol` (absolute rtol * 1e-3).
Run solve_shooting_cvode(const rod::RodModel& model, double rtol, double tolerance);

/// FE discretization and Newton tolerances (beam_fe::Options).
struct FeSettings {
  int elements = 16;
  int order = 2;
  double tolerance_abs = 1e-12;  ///< [N, N m], beam_fe::Options::tolerance_abs
  double tolerance_rel = 1e-10;  ///< beam_fe::Options::tolerance_rel
};
/// FE solve of the model's own actuation.
Run solve_fe(const rod::RodModel& model, const FeSettings& settings);

/// Settings of the shooting reference.
struct ReferenceSettings {
  int steps = 2048;           ///< RK4 steps of the reference (even; steps / 2 also even)
  double cvode_rtol = 1e-12;  ///< second opinion; <= 0 skips it
  /// Newton tolerance on the scaled shooting residual (RK4 solves): below cosserat's default
  /// (1e-10), whose tip error reaches 1e-9 L on the slender steel rod; 1e-13 is below the
  /// round-off floor of that rod's residual (its solve fails). CVODE keeps 1e-10.
  double tolerance = 1e-12;
};

/// The shooting reference of one model.
struct Reference {
  Run rk4;       ///< RK4 with `steps`: the reference
  Run rk4_half;  ///< RK4 with steps / 2
  /// Estimated tip error of the reference [m]: |p(steps) - p(steps/2)| / 15 (RK4's order 4);
  /// with obstacles |p(steps) - p(steps/2)| itself (the contact points are the grid's nodes, so
  /// the contact ends are resolved to the grid: about first order, docs/conventions.md).
  double self_error_m = 0.0;
  /// Second opinion (when asked for; not with obstacles: CVODE's adaptive steps have no
  /// contact nodes).
  std::optional<Run> cvode;
  double cvode_difference_m = 0.0;  ///< |p_cvode - p_rk4| [m]
  bool converged() const;           ///< every solve converged
};
/// Solves the reference (throws nothing for non-convergence: see converged()).
Reference shooting_reference(const rod::RodModel& model, const ReferenceSettings& settings);

using tcasim::observed_orders;  // common/convergence.hpp

/// Richardson extrapolation from three levels h0 > h1 > h2 with a common ratio
/// r = h0/h1 = h1/h2 (within 1e-9 relative; std::invalid_argument otherwise) of the vector
/// values u0, u1, u2 (e.g. tip positions):
///   p = log(|u0 - u1| / |u1 - u2|) / log r,   u* = u2 + (u2 - u1) / (r^p - 1).
struct Richardson {
  double order = 0.0;     ///< p (NaN when a difference is zero or not finite)
  Eigen::Vector3d value;  ///< u*
};
Richardson richardson(const std::vector<double>& h, const std::vector<Eigen::Vector3d>& u);

/// One level of a convergence study.
struct ConvergenceLevel {
  int elements = 0;
  double h_m = 0.0;                 ///< element length L / elements
  Run fe;                           ///< the FE solve
  double error_m = 0.0;             ///< |p_fe(s) - p_ref(s)| at s = measured_arc_length
  double observed_order = 0.0;      ///< from this level and the previous one (NaN at the first)
  double richardson_error_m = 0.0;  ///< |p_fe(L) - u*| against the Richardson extrapolation
  /// Round-off floor estimate of this mesh's position error (fe_round_off_floor_m).
  double floor_estimate_m = 0.0;
  /// Beyond the asymptotic range: refinement stopped helping at or before this level
  /// (ConvergenceStudy::asymptotic_levels); its order is not the discretization's.
  bool round_off = false;
};

/// A convergence study of one model and one order.
struct ConvergenceStudy {
  int order = 2;
  double measured_s_m = 0.0;             ///< arc length of the measured point
  std::vector<ConvergenceLevel> levels;  ///< coarse to fine
  /// Leading levels in the asymptotic range (asymptotic_level_count); the others are
  /// flagged round_off and their orders are excluded from asymptotic_order and the gates.
  int asymptotic_levels = 0;
  /// Observed order of the two finest asymptotic levels (NaN with fewer than two).
  double asymptotic_order = 0.0;
  /// From the three finest asymptotic levels (the three finest levels when fewer than three
  /// are asymptotic: then its order is not the discretization's either).
  Richardson richardson;
  bool converged() const;  ///< every FE solve converged
};
/// Solves the FE on each element count (increasing, a common refinement ratio), with the
/// given Newton tolerances, and measures errors against `reference` and against the
/// Richardson extrapolation of its three finest levels. `progress` (may be empty) is
/// called before each solve with a short text.
ConvergenceStudy convergence_study(const rod::RodModel& model, const Reference& reference,
                                   const FeSettings& tolerances, const std::vector<int>& elements,
                                   const std::function<void(const std::string&)>& progress = {});

/// Observed-order bracket of an FE order (the FE issue): linear 2 +- 0.15, quadratic 4 +- 0.3.
struct OrderBracket {
  double expected;
  double tolerance;
  double lo() const { return expected - tolerance; }
  double hi() const { return expected + tolerance; }
  bool contains(double p) const { return p >= lo() && p <= hi(); }  ///< NaN is outside
};
/// Bracket for order 1 or 2 (std::invalid_argument otherwise).
OrderBracket order_bracket(int order);

/// Round-off floor estimate of the beam FE's positions on a mesh of `elements` elements of
/// `order`: the displacement formulation resolves strains, differences of nodal positions, to
/// about eps per node, so its Newton iteration stops at force residuals of order
/// eps nodes max(EA, GA) (beam_fe round_off_floor, which allows 10 times that), which the
/// bending compliance L^2 / min(EI) turns into eps nodes max(EA, GA) L^2 / min(EI) times L
/// (measured on Mattiasson's cantilever, k = 5, quadratic: at EA L^2 / EI = 1e8, 1.9e-6 L at
/// 128 elements against 5.7e-6 L; at 1e10, 1.4e-6 L at 16 elements against 7.3e-6 L). An
/// upper estimate: Newton may happen to stop far below it.
double fe_round_off_floor_m(const rod::RodModel& model, int order, int elements);

/// Number of leading levels inside the asymptotic range: the range ends before the first
/// level i >= 1 whose observed order (from levels i - 1, i) is below the bracket (or NaN,
/// or the error grew) while its error is at most floors_m[i], i.e. where refinement stopped
/// helping because the error reached the round-off floor. A low order above the floor is
/// not explained by round-off and stays in the range (the order gates then fail).
int asymptotic_level_count(const std::vector<double>& h, const std::vector<double>& errors,
                           const OrderBracket& bracket, const std::vector<double>& floors_m);

/// One row of a cross-check: an FE mesh against the shooting reference.
struct CrossCheckRow {
  std::string scenario;
  double length_m = 0.0;  ///< body length L
  int elements = 0;
  int order = 0;
  ResultDifference diff;         ///< fe - reference
  double cosserat_time_s = 0.0;  ///< reference solve (RK4, `reference steps`)
  double fe_time_s = 0.0;
  bool converged = false;  ///< FE and reference converged
};
/// Cross-checks each FE mesh of `meshes` (elements, order, tolerances) against the reference.
std::vector<CrossCheckRow> cross_check(
    const rod::RodModel& model, const Reference& reference, const std::vector<FeSettings>& meshes,
    const std::function<void(const std::string&)>& progress = {});

/// CSV header and rows of crosscheck.csv (columns in the header, units in their names).
std::string crosscheck_csv_header();
std::string crosscheck_csv_row(const CrossCheckRow& row, const Reference& reference,
                               int reference_steps);
/// CSV header and rows of convergence.csv.
std::string convergence_csv_header();
std::string convergence_csv_rows(const std::string& scenario, const ConvergenceStudy& study);
/// Text table of a study: elements, h, error vs shooting, observed order, error vs Richardson.
std::string convergence_table(const ConvergenceStudy& study);

/// Element counts base, base r, ..., base r^(levels - 1) (r = 2).
std::vector<int> refinement_levels(int coarsest, int levels);

/// Levels of a study, chosen inside the asymptotic range (coarser: pre-asymptotic; finer:
/// the error reaches the round-off floor or the reference's accuracy).
struct StudyLevels {
  int coarsest;
  int count;
  std::string reason;  ///< why a scenario departs from the default levels (empty: default)
};
/// Levels for order 1 or 2, full or quick, for the named scenario (the suite's exceptions
/// are listed with their measured reason in crosscheck.cpp).
StudyLevels study_levels(const std::string& scenario, int order, bool quick);

/// Meshes of the cross-check (tight tolerances): quadratic at increasing refinement (the
/// finest is gated), then linear. Quick: fewer meshes, same finest quadratic mesh.
std::vector<FeSettings> crosscheck_meshes(bool quick);

/// Newton tolerances of the convergence studies: tighter than beam_fe's defaults so the
/// solver error stays below the discretization error (the solver's round-off floor still
/// applies, see beam_fe::Discretization::round_off_floor).
FeSettings tight_tolerances();

}  // namespace tcasim::crosscheck
