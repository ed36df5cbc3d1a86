#pragma once
/// The result file `tcasim.result/1` (docs/scenario-format.md), written by both solvers.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rod/model.hpp"
#include "rod/obstacle.hpp"

namespace tcasim::rod {

/// State of one actuator in a solution (per string: a `count` of 2 has this tension in each).
struct ActuatorResult {
  ActuatorResult() = default;
  ActuatorResult(std::string name_, double tension, double elongation)
      : name(std::move(name_)), tension_N(tension), elongation_m(elongation) {}
  std::string name;
  double tension_N = 0.0;     ///< tension of one string (positive = tensile)
  double elongation_m = 0.0;  ///< current length minus rest length of one string
  /// TCA drives: coil contact in the solved state (set_coil_contacts). True when the TCA, or
  /// any segment of a segmented one, sits at its closed length held by coil contact.
  bool coils_closed = false;
  /// The contact force of the closed coils [N] (>= 0; the largest over the segments).
  double contact_force_N = 0.0;
  bool is_tca = false;  ///< a TCA drive: the contact fields are written
  /// Segmented TCA drives: each segment's temperature [K] and contact state, base to tip.
  std::vector<std::pair<tca::Segment, tca::SegmentContact>> segments;
};

/// A probe of the model in a solution (docs/scenario-format.md "Probes and frames").
struct ProbeResult {
  std::string name;
  Eigen::Vector3d position_W_m = Eigen::Vector3d::Zero();  ///< p(s) + R(s) offset, world frame
};

/// A force and a moment (world frame; the moment about a stated point).
struct Wrench {
  Eigen::Vector3d force_W_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_W_Nm = Eigen::Vector3d::Zero();
};

/// One solve's outcome, as written to a result file.
struct Result {
  std::string scenario;  ///< RodModel::name
  std::string method;    ///< "cosserat" or "fe"
  /// Discretization as key/value pairs, e.g. {{"steps", 100}} or {{"elements", 32}, {"order", 2}}.
  std::vector<std::pair<std::string, double>> discretization;
  bool converged = false;
  /// "converged", or the solver's reason for stopping (docs/scenario-format.md); "not_run"
  /// for a result no solve filled.
  std::string status = "not_run";
  /// Iterations of the solve: shooting, Newton iterations over all levels and continuation
  /// steps; FE, Newton and chord iterations (linear solves) over all load steps.
  int iterations = 0;
  /// The residual both methods report (docs/scenario-format.md "residual"): the largest
  /// unbalanced force at the returned state and the full loads (moments divided by L) over
  /// characteristic_force_N; empty when it could not be evaluated (written as null).
  std::optional<double> residual;
  double characteristic_force_N = 0.0;  ///< F_c [N] (rod::characteristic_force_N)
  double wall_time_s = 0.0;
  std::string message;  ///< why it did not converge (empty when converged)

  Eigen::Vector3d tip_position_W_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d tip_R_WB = Eigen::Matrix3d::Identity();
  std::vector<ActuatorResult> actuators;
  std::optional<double> bending_radius_m;  ///< three-point inner-edge radius; none when straight
  std::optional<Eigen::Vector3d> tip_reaction_force_W_N;  ///< with a tip constraint

  /// Centerline samples: arc length, position and body frame at each.
  std::vector<double> centerline_s_m;
  std::vector<Eigen::Vector3d> centerline_p_W_m;
  std::vector<Eigen::Matrix3d> centerline_R_WB;
  /// The model's probes, evaluated by the solver exactly at their s (empty without probes or
  /// without a solution; written as `probes` only when non-empty).
  std::vector<ProbeResult> probes;
  /// One entry per model obstacle, in file order (docs/scenario-format.md "Obstacles");
  /// empty without obstacles (written as `contacts` only when the model has obstacles).
  std::vector<ContactResult> contacts;
  /// What the clamp applies to the rod (world frame, moment about the base point); written
  /// as `base_reaction` when set. Base reaction + weight + tip loads + contacts balance.
  std::optional<Wrench> base_reaction;
};

/// Serializes a result. Non-finite numbers are never written: a result holding one is
/// turned into converged = false with a message naming the field.
nlohmann::json to_json(const Result& result);

/// Fills the coil-contact fields of `out` for a TCA-driven actuator from its solved tension
/// (out.tension_N) and the segment temperatures the solve used (tca::segment_contacts); does
/// nothing for a tension drive. Both solvers call it when they fill a result.
void set_coil_contacts(const Actuator& actuator, const std::vector<tca::Segment>& segments,
                       ActuatorResult& out);

/// JSON text with objects indented by two spaces per level and every array of scalars
/// (numbers, strings, booleans, nulls) on one line, e.g. a position [x, y, z], so a
/// centerline takes one line per sample and a rotation matrix three. Numbers are written as
/// by nlohmann::json::dump (shortest round-trip form); the text parses to `j`.
std::string format_json(const nlohmann::json& j);

/// Writes format_json(to_json(result)) to `path`, or to stdout when path is empty or "-".
void write_result(const Result& result, const std::string& path);

/// The paper's bending-radius metric (Fig. 6): the circle through three points on the
/// inner edge of the body (base, middle, tip) on the side toward the bending direction,
/// at the section's half extent from the centerline. `s`, `p` and `R` sample the
/// centerline in increasing s (at least 2 samples, first at the base, last at the tip).
/// Bending direction u_B: the base-to-tip chord in the base body frame, projected on the
/// section plane (points to the centre of curvature of any planar arc, precurved or not).
/// Edge points: p_k + R_k h(u) (u_x, u_y, 0). The middle pose at (s_0 + s_end)/2 is a
/// sample if one lies there, else the constant-strain (SE(3) geodesic) interpolation of
/// its two neighbours, exact for arcs and helices. Returns none when the lateral tip
/// offset is below 1e-12 L or the points are collinear (a straight rod), and for a custom
/// section (no outline, so no inner edge).
std::optional<double> three_point_inner_radius(const RodModel& model,
                                               const std::vector<double>& s_m,
                                               const std::vector<Eigen::Vector3d>& p_W_m,
                                               const std::vector<Eigen::Matrix3d>& R_WB);

}  // namespace tcasim::rod
