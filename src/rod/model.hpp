#pragma once
/// The shared description of a rod robot with embedded string actuators, read from a
/// scenario file (docs/scenario-format.md). Immutable once built; both solvers read it.
///
/// Frames: world W (fixed; the base clamp is at `base_position_W` with body frame
/// `R_WB0`), body B (e1, e2 span the section, e3 along the undeformed centerline).
/// Units: SI throughout; temperatures in kelvin.
#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/time_profile.hpp"
#include "rod/obstacle.hpp"
#include "rod/profile.hpp"
#include "tca/tca.hpp"
#include "tca/thermal.hpp"

namespace tcasim::rod {

/// Derived properties of the section at one s.
struct SectionProperties {
  double width_m = 0.0, height_m = 0.0;  ///< circle: both the diameter
  double area_m2 = 0.0, I_x_m4 = 0.0, I_y_m4 = 0.0, J_m4 = 0.0;
};

/// The body material's values at one s.
struct MaterialProperties {
  double youngs_modulus_Pa = 0.0;  ///< E
  double shear_modulus_Pa = 0.0;   ///< G = E / (2 (1 + nu))
  double density_kg_m3 = 0.0;      ///< psi
  double viscosity_Pa_s = 0.0;     ///< eta, Kelvin-Voigt
};

/// The diagonal section matrices of a linear isotropic law at one s.
struct SectionStiffness {
  Eigen::Vector3d shear_extension;  ///< diag(G A, G A, E A)
  Eigen::Vector3d bending_torsion;  ///< diag(E I_x, E I_y, G J)
};

/// The one derivation of the section matrices from a tensile modulus E and a shear modulus G
/// ([Pawlowski2019] text below Eq. (12), no shear correction factor): with the elastic moduli
/// [Pa] the stiffnesses K_nu [N] and K_omega [N m^2]; with the Kelvin-Voigt viscosities eta
/// and eta_s [Pa s] the damping B_se [N s] and B_bt [N m^2 s].
SectionStiffness section_stiffness(const SectionProperties& p, double E, double G);

/// Saint-Venant torsion constant of a w x h rectangle [m^4] ([TimoshenkoGoodier1970] Sec. 109).
double rectangle_saint_venant_torsion(double w_m, double h_m);

/// Cross-section of the body: its shape and the scalars the file gives, each a profile along s
/// (docs/scenario-format.md "Profiles along the body"; a constant is a one-piece profile). The
/// derived properties are not stored: properties_at() computes them at each s.
struct Section {
  enum class Shape { kCircle, kRectangle, kCustom };
  Shape shape = Shape::kCircle;
  bool saint_venant_torsion = false;  ///< rectangle: J by Saint-Venant, else polar
  /// The scalars the file gives: circle: width (the diameter; height the same); rectangle:
  /// width (along body x), height (along body y) [m]; custom: area A [m^2], I_x (int y^2 dA),
  /// I_y (int x^2 dA), J (torsion constant) [m^4].
  Profile width_profile, height_profile, area_profile, I_x_profile, I_y_profile, J_profile;
  /// custom: the radius of the circle it touches obstacles with (`contact_radius_m`); a
  /// custom section without it cannot touch (docs/scenario-format.md "Obstacles").
  std::optional<double> contact_radius_m;
  /// The properties at s (at a jump: the limit from `side`): a circle's I is pi d(s)^4 / 64,
  /// its J (and a rectangle's unless Saint-Venant) the polar moment I_x + I_y.
  SectionProperties properties_at(double s, Side side = Side::kRight) const;
  /// d/ds of properties_at (the slopes of the profiles through the shape's formulas; the
  /// Saint-Venant J of a rectangle by central differences of its series in w and h).
  SectionProperties derivatives_at(double s, Side side = Side::kRight) const;
  /// True if any given scalar is a profile.
  bool varies() const;
  /// Half extent of the section at the base (s = 0) along the direction (dir_x, dir_y) in the
  /// section plane (any non-zero length) [m]: the distance from the centerline to the edge,
  /// used by the radius metric and the actuator-offset check. Circle: D/2; rectangle: distance
  /// to the first edge the ray meets. Throws DomainError for a custom section (it has no
  /// outline) and for a zero or non-finite direction.
  double half_extent_m(double dir_x, double dir_y) const;
};

/// Linear elastic, isotropic body material: E, psi and eta are profiles along s (a constant is
/// a one-piece profile), G is not stored but derived from E and nu (shear_modulus()).
struct BodyMaterial {
  Profile youngs_modulus_profile;  ///< E [Pa]
  double poisson_ratio = 0.0;      ///< nu
  Profile density_profile;         ///< psi [kg/m^3] (0 allowed: massless)
  Profile viscosity_profile;       ///< eta [Pa s], Kelvin-Voigt (dynamics only; >= 0)
  /// G = E / (2 (1 + nu)) of a tensile modulus E [Pa]; of a Kelvin-Voigt viscosity eta, the
  /// shear viscosity eta_s [Pa s] likewise.
  double shear_modulus(double youngs_modulus) const {
    return youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  }
  /// E, G, psi and eta at s (at a jump: the limit from `side`).
  MaterialProperties properties_at(double s, Side side = Side::kRight) const;
  /// True if E or psi is a profile (eta is the dynamics' business: it reads viscosity_profile).
  bool varies() const;
};

/// Path of a string in the body frame: r(s) = (x, y, 0) in the section plane.
struct Routing {
  enum class Type { kStraight, kHelix, kSpline };
  Type type = Type::kStraight;
  Eigen::Vector2d offset_m = Eigen::Vector2d::Zero();  ///< straight: constant offset
  double radius_m = 0.0;                               ///< helix radius
  double phase_rad = 0.0;                              ///< helix phase at s = 0
  double turns_per_m = 0.0;                            ///< helix turns per metre of arc length s
  /// Spline (docs/scenario-format.md "General routing and string extent"): the offsets
  /// knot_offsets_m[j] at the knots knot_s_m[j] (strictly increasing, at least two), joined
  /// by straight pieces (`linear`) or a C2 natural cubic spline per coordinate, whose second
  /// derivatives at the knots are knot_curvatures (zero at both ends; all zero if linear).
  std::vector<double> knot_s_m;
  std::vector<Eigen::Vector2d> knot_offsets_m, knot_curvatures;
  bool linear = false;

  /// Sets knot_curvatures from knot_s_m and knot_offsets_m (the natural spline's tridiagonal
  /// system; zeros for `linear`). rod/spline_routing.cpp.
  void build_spline();
  /// Whether r' may jump at the spline knot knot_s_m[j] (a `linear` routing's interior knot).
  bool kinked() const { return type == Type::kSpline && linear; }

  /// r_B(s), r_B'(s), r_B''(s) (derivatives with respect to the reference arc length s). At a
  /// spline knot `side` picks the piece (kRight: the one starting there); outside the knots
  /// a spline continues its end pieces. Straight and helix ignore `side`.
  Eigen::Vector3d r(double s_m, Side side = Side::kRight) const;
  Eigen::Vector3d dr(double s_m, Side side = Side::kRight) const;
  Eigen::Vector3d ddr(double s_m, Side side = Side::kRight) const;

 private:
  /// The spline piece index j (knot_s_m[j] <= s <= knot_s_m[j + 1]) holding s on `side`.
  std::size_t spline_piece(double s_m, Side side) const;
  /// Value (derivative 0), slope (1) or second derivative (2) of the spline at s.
  Eigen::Vector3d spline_eval(double s_m, Side side, int derivative) const;
};

/// The electric drive of one TCA segment (docs/scenario-format.md "Electro-thermal TCAs").
struct ElectricSegment {
  tca::ElectricInput input = tca::ElectricInput::kVoltage;
  TimeProfile value;  ///< voltage [V], current [A] or power [W] over time
  /// The segment's share of the TCA's thermal parameters (fraction f of C, hA and R0).
  tca::ThermalParameters thermal;
};

/// How a string's tension is set.
struct Drive {
  enum class Type { kTension, kTca };
  Type type = Type::kTension;
  double tension_N = 0.0;               ///< kTension: prescribed tension (positive = tensile)
  std::string tca_id;                   ///< kTca: key into RodModel::tcas
  std::shared_ptr<const tca::Tca> tca;  ///< kTca: the resolved TCA
  std::vector<tca::Segment> segments;   ///< kTca: one segment {1, T} for a uniform temperature
  bool segmented = false;               ///< true if the file gave `segments`
  /// Time profiles of the drive (docs/scenario-format.md "Time profiles"); tension_N and
  /// segments[k].temperature_K hold their values at t = 0.
  TimeProfile tension_profile_N;                    ///< kTension
  std::vector<TimeProfile> temperature_profiles_K;  ///< kTca by temperature: one per segment
  /// kTca by electric input: one per segment (empty for a temperature drive); the segments'
  /// temperatures at t = 0 are the steady temperatures of the inputs at t = 0.
  std::vector<ElectricSegment> electric;
  bool is_electric() const { return !electric.empty(); }
};

/// One actuator: `count` identical parallel strings along one routing.
struct Actuator {
  std::string name;
  Routing routing;
  int count = 1;
  Drive drive;
  /// TCA drive: the TCA's elongation in the reference configuration [m] (signed; the
  /// scenario's `pre_elongation_m`, 0 when absent: the coiled length is the path length).
  double pre_elongation_m = 0.0;
  /// Rest length of one string [m], what the solvers subtract from the current path length
  /// to get the elongation: the reference path length int over the span of
  /// |e3 + omega* x r + r'| ds (rod/reference_path.hpp), less pre_elongation_m for a TCA drive.
  double rest_length_m = 0.0;
  /// Where the string is anchored to the body, [s_start, s_end] (docs/scenario-format.md
  /// "String extent"): absent = [0, L]. Outside its span the string carries nothing; an
  /// anchor inside (0, L) applies the string's end force there (rod/routing.cpp).
  std::optional<std::array<double, 2>> span_m;
  double span_start_m() const { return span_m ? (*span_m)[0] : 0.0; }
  double span_end_m(double body_length_m) const { return span_m ? (*span_m)[1] : body_length_m; }
  /// True if the string ends inside the body (a span other than [0, L]).
  bool anchored_inside(double body_length_m) const {
    return span_start_m() > 0.0 || span_end_m(body_length_m) < body_length_m;
  }
};

/// Tip held at a world point: fully (pinned), or only along a contact normal.
struct TipConstraint {
  Eigen::Vector3d position_W_m = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> normal_W;  ///< unit; absent = pinned
};

/// A point fixed to the body (docs/scenario-format.md "Probes and frames"): a marker, a
/// sensor or a contact point at arc length s with an offset in the body frame there.
struct Probe {
  std::string name;  ///< unique; names the CSV columns <name>_x_m, <name>_y_m, <name>_z_m
  double s_m = 0.0;  ///< reference arc length, in [0, L]
  Eigen::Vector3d offset_B_m = Eigen::Vector3d::Zero();  ///< (x, y) in the section, z along e3
};

/// Everything a solver needs to know about one rod robot.
struct RodModel {
  std::string schema;
  std::string name;
  std::string comment;
  double length_m = 0.0;  ///< L, reference centerline length
  Section section;
  BodyMaterial material;
  /// omega* [1/m] along s, per body-frame component (constants unless the file gives profiles;
  /// reference_curvature_at() reads it).
  std::array<Profile, 3> reference_curvature_profile;
  Eigen::Vector3d gravity_W_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d tip_force_W_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d tip_moment_W_Nm = Eigen::Vector3d::Zero();
  Eigen::Vector3d base_position_W_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WB0 = Eigen::Matrix3d::Identity();
  std::optional<TipConstraint> tip_constraint;
  /// Point mass at the tip [kg] (`tip_mass_kg`, default 0): in statics a tip weight
  /// m g added to the tip force (rod::tip_force_with_weight_W_N).
  double tip_mass_kg = 0.0;
  /// Time profiles of the tip wrench components (world frame); tip_force_W_N and
  /// tip_moment_W_Nm hold their values at t = 0.
  std::array<TimeProfile, 3> tip_force_profile_W_N;
  std::array<TimeProfile, 3> tip_moment_profile_W_Nm;
  std::map<std::string, std::shared_ptr<const tca::Tca>> tcas;
  /// Lumped thermal parameters of the TCAs that have a `thermal` block, by TCA id.
  std::map<std::string, tca::ThermalParameters> tca_thermal;
  std::vector<Actuator> actuators;
  /// Body-fixed points both solvers report exactly at their s (`probes`, default none).
  std::vector<Probe> probes;
  /// Rigid obstacles the rod may touch (`obstacles`, default none), in file order.
  std::vector<Obstacle> obstacles;

  // --- Properties along s (docs/scenario-format.md "Profiles along the body"), all read from
  // the profiles of section, material and omega*. At a breakpoint where a profile jumps,
  // `side` selects the one-sided limit. Without s: the values at the base, s = 0, which are
  // those of every s for a uniform body (a constant profile returns its one value, so a uniform
  // body's properties are the same numbers at every s).
  /// True if no section scalar, E, density or omega* component varies along s.
  bool uniform_body() const;
  /// K_nu and K_omega at s: section_stiffness() of the section there with E(s) and G(s).
  SectionStiffness stiffness_at(double s, Side side = Side::kRight) const;
  /// K_nu = diag(G A, G A, E A) at s [N].
  Eigen::Vector3d shear_extension_stiffness(double s = 0.0, Side side = Side::kRight) const;
  /// K_omega = diag(E I_x, E I_y, G J) at s [N m^2].
  Eigen::Vector3d bending_torsion_stiffness(double s = 0.0, Side side = Side::kRight) const;
  /// psi(s) A(s) [kg/m].
  double mass_per_length_kg_m(double s, Side side = Side::kRight) const;
  /// Weight per unit length psi A g at the base in the world frame [N/m].
  Eigen::Vector3d weight_per_length_W_N_m() const;
  /// omega*(s) [1/m] (body frame).
  Eigen::Vector3d reference_curvature_at(double s, Side side = Side::kRight) const;
  /// Sets omega* constant along s [1/m] (body frame).
  void set_reference_curvature(const Eigen::Vector3d& omega_B_1_m);
  /// d/ds of the two stiffnesses and of omega* at s (zero for a uniform body): what the
  /// shooting right-hand side needs, n_B' = K_nu e' + K_nu' e and likewise for m_B.
  void property_slopes(double s, Side side, Eigen::Vector3d& dK_se, Eigen::Vector3d& dK_bt,
                       Eigen::Vector3d& domega_star) const;
  /// Every listed s of every profile strictly inside (0, L), sorted, without repeats.
  std::vector<double> breakpoints() const;
  /// Whether any property jumps at s (left and right limits differ).
  bool jumps_at(double s) const;
  /// Every string anchor strictly inside (0, L) (rod/routing.cpp), sorted, without repeats:
  /// the points where a string's share of the section wrench starts or stops.
  std::vector<double> anchor_points() const;
  /// breakpoints(), anchor_points() and routing_knots() together, sorted, without repeats:
  /// where the FE mesh puts a node and the shooting integrator a piece boundary.
  std::vector<double> interior_knots() const;
  /// Every interior knot of a spline routing strictly inside (0, L) (rod/routing.cpp), sorted,
  /// without repeats: where r'' (cubic) or r' (linear) may change abruptly.
  std::vector<double> routing_knots() const;
  /// The routing knots where a `linear` spline string's direction may jump (a kink): the
  /// string's point force on the body there.
  std::vector<double> routing_kinks() const;
  /// True if any string is anchored inside the body.
  bool has_inner_anchors() const;
};

/// A copy of `model` with every TCA rebuilt on `material` (measurable parameters kept; the
/// Eq. (4) factor replaced when `f12_form` is given), the actuators pointing at the new TCAs.
RodModel with_tca_material(const RodModel& model, const tca::Material& material,
                           std::optional<tca::F12Form> f12_form = std::nullopt);

}  // namespace tcasim::rod
