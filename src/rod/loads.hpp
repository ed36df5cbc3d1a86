#pragma once
/// The loads of a rod model that a sweep, an inverse solve or a continuation may change
/// without rebuilding the model: per actuator its tension (tension drive) or its segments'
/// temperatures (TCA drive), the tip wrench, gravity, and a load scale. Both solvers take
/// them (cosserat::ShootingSolver::solve, beam_fe::solve); Loads::from_model gives the loads
/// the scenario file describes.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "rod/model.hpp"
#include "tca/tca.hpp"

namespace tcasim::rod {

/// The load of one actuator: which field is read depends on the model's drive type.
struct ActuatorLoad {
  double tension_N = 0.0;  ///< tension drive: tension of one string (positive = tensile)
  std::vector<tca::Segment> segments;  ///< TCA drive: segment fractions and temperatures [K]
};

/// Everything a solve may change without rebuilding the model (world frame W, SI).
struct Loads {
  std::vector<ActuatorLoad> actuators;  ///< one per model actuator, in model order
  Eigen::Vector3d tip_force_W_N = Eigen::Vector3d::Zero();    ///< applied to the rod at the tip
  Eigen::Vector3d tip_moment_W_Nm = Eigen::Vector3d::Zero();  ///< applied to the rod at the tip
  Eigen::Vector3d gravity_W_m_s2 = Eigen::Vector3d::Zero();
  /// Load scale s in [0, 1]: the solvers apply applied(model), i.e. s times the tensions, tip
  /// wrench and gravity, and temperatures T_ref + s (T - T_ref) (T_ref the TCA material's
  /// reference temperature). 1 (the default) applies the loads as given.
  double load_scale = 1.0;

  /// The loads the model file describes (load_scale 1): its time profiles at t = 0, an
  /// electric drive's segments at the steady temperatures of its inputs at t = 0.
  static Loads from_model(const RodModel& model);
  /// The loads at time t_s: from_model with every non-constant time profile (tension, segment
  /// temperature, tip wrench component) evaluated at t_s, and each electric drive's segments
  /// at the steady temperature of its input at t_s (the quasi-static thermal limit; a dynamic
  /// simulation replaces them by its thermal states). Throws DomainError when an input at
  /// t_s has no steady temperature (thermal runaway).
  static Loads at_time(const RodModel& model, double t_s);
  /// Sets every segment of TCA actuator `index` to temperature t_K [K].
  void set_temperature_K(std::size_t index, double t_K);
  /// Sets the segment temperatures of TCA actuator `index` [K], one per segment.
  void set_segment_temperatures_K(std::size_t index, const std::vector<double>& t_K);
  /// Sets the tension of one string of tension-driven actuator `index` [N].
  void set_tension_N(std::size_t index, double tension_N);

  /// Throws InputError (key `loads....`, value, rule) unless the loads fit `model`: one entry
  /// per actuator, non-empty segments for a TCA drive, finite values, load_scale in [0, 1].
  void validate(const RodModel& model) const;
  /// The same loads with load_scale folded in (load_scale 1; an exact copy when it is 1).
  Loads applied(const RodModel& model) const;
};

/// The loads at time t [s] (a simulation's drive: constant, or time profiles).
using LoadsAt = std::function<Loads(double t_s)>;

/// Characteristic force F_c [N] of the residual both methods report (docs/scenario-format.md
/// "residual"), of loads.applied(model): F_c = max(min(E I_x, E I_y) / L^2, |F_e|, |M_e| / L,
/// rho A |g| L, c_i |T_i| of the tension drives). The shooting solver scales its residual by
/// F_c of the model's own loads (cosserat/shooting.hpp).
double characteristic_force_N(const RodModel& model, const Loads& loads);
/// characteristic_force_N with the tip point mass tip_mass_kg in place of the model's (a
/// dynamics option may replace it).
double characteristic_force_N(const RodModel& model, const Loads& loads, double tip_mass_kg);

/// The force on the rod at its tip including the tip mass's weight [N] (world frame):
/// loads.tip_force_W_N + model.tip_mass_kg loads.gravity_W_m_s2 (exactly tip_force_W_N when
/// the tip mass is 0). Both solvers apply this in statics.
Eigen::Vector3d tip_force_with_weight_W_N(const RodModel& model, const Loads& loads);

}  // namespace tcasim::rod
