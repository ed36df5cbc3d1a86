#pragma once
/// Geometrically exact (Simo-Reissner) beam finite elements with embedded string
/// actuators: the same continuum problem as the Cosserat shooting solver
/// (docs/conventions.md), discretized in a total-Lagrangian form.
///
/// Element: Lagrange interpolation of order 1 or 2 of the centerline p_W; nodal triads
/// R_WB as unit quaternions; rotations interpolated objectively and path-independently
/// [Crisfield1999], [Jelenic1999]: with a reference node triad R_r (node 0 for order 1, the
/// middle node for order 2), local rotation vectors psi_a = log(R_r^T R_a) are
/// interpolated, R(s) = R_r exp(psi(s)). Strains nu_B = R^T p', omega_B = Jr(psi) psi'.
/// Nodal increments are material: R_a <- R_a exp(dtheta_a), p_a <- p_a + dp_a.
///
/// Strings enter as an internal potential c_i T_i l_i(q), l_i = int_0^L |q_i| ds with
/// q_i = nu + omega x r_i + r_i' at the quadrature points; a TCA drive adds its tension
/// as a global unknown with the residual T_i - F_tca(l_i - rest_length_i, temperatures)
/// (bordered system). Gravity and the tip force are dead loads; the tip moment is fixed in
/// the world frame (virtual work M_e . dtheta_W, i.e. m(L) = M_e as in the shooting solver).
///
/// Obstacles (rod::RodModel::obstacles, rod/obstacle.hpp) touch the mesh nodes: every free
/// node against every obstacle and contact candidate of its section (rod::section_gaps) has
/// a contact force lambda n at p + c with a multiplier lambda >= 0 as an unknown and the
/// complementarity row min(lambda, k g) = 0 (k = max(EA, GA)/L); each Newton step solves the
/// contact problem linearized at the iterate exactly, so the contact set (primal-dual active
/// set) is updated every iteration (docs/conventions.md "Contact in the FE").
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::beam_fe {

/// Gauss rule per element.
enum class Integration {
  kReduced,  ///< p Gauss points for order p (1 for linear, 2 for quadratic): no locking
  kFull,     ///< p + 1 Gauss points (2 for linear, 3 for quadratic): locks on slender rods
};

/// Sparse direct solver for the (non-symmetric) Newton systems. UMFPACK lives in a plugin,
/// libtcasim_umfpack.so, loaded at its first use (load_linear_solver).
enum class LinearSolver { kKlu, kUmfpack, kSparseLu };

/// Discretization and solver settings.
struct Options {
  int elements = 16;  ///< number of elements, >= 1
  int order = 2;      ///< Lagrange order, 1 or 2
  Integration integration = Integration::kReduced;
  LinearSolver linear_solver = LinearSolver::kKlu;
  double tolerance_abs = 1e-12;    ///< absolute residual tolerance [N, N m]
  double tolerance_rel = 1e-10;    ///< relative to the load scale (see Summary::Status)
  int max_iterations = 30;         ///< Newton iterations (linear solves) per load step
  int max_load_steps = 200;        ///< load-step attempts (accepted + rejected)
  double initial_load_step = 1.0;  ///< first load-factor increment in (0, 1]
  double min_load_step = 1e-6;     ///< give up when a halved increment falls below this
  /// With obstacles: Newton iterations of one load step that may change the contact set
  /// (active pairs); one more change fails the step (Summary::Status::kContactNotSettled
  /// when no load step can then reach lambda = 1).
  int max_contact_changes = 12;
  /// More points strictly inside (0, L) where the mesh puts a node, as at a breakpoint of the
  /// body's profiles (the FE dynamics passes the breakpoints of a viscosity profile). Empty
  /// (the default): the mesh of the body's own breakpoints and anchors.
  std::vector<double> extra_knots_m;
};

/// Configuration of the mesh: nodal positions, triads and string tensions.
struct State {
  std::vector<double> s_m;               ///< reference arc length of each node
  std::vector<Eigen::Vector3d> p_W_m;    ///< nodal centerline positions
  std::vector<Eigen::Quaterniond> q_WB;  ///< nodal triads (unit quaternions)
  std::vector<double> tensions_N;        ///< per actuator, tension of one string
  /// With a tip_constraint: the force the holder applies to the rod at the tip (world frame);
  /// along the normal for a normal-only contact. Zero without a constraint.
  Eigen::Vector3d tip_reaction_W_N = Eigen::Vector3d::Zero();
  double load_factor = 0.0;  ///< lambda of the last accepted load step
  /// With obstacles: the contact multiplier lambda >= 0 of every contact pair [N]: per free
  /// node k = 1 .. nodes - 1, per obstacle o, per contact candidate c of its section
  /// (rod::section_gaps: 1 for a circle, 8 for a rectangle), index ((k - 1) n_obstacles + o)
  /// n_candidates + c (the normal force on the rod at that candidate's touching point). Empty
  /// without obstacles. It carries the contact set of a warm start: a pair is active where
  /// lambda - k g > 0.
  std::vector<double> contact_lambda_N;
};

/// Outcome of a solve.
struct Summary {
  enum class Status {
    /// At load factor 1, every residual row |r_i| <= tolerance_abs + tolerance_rel * scale
    /// + floor_i, where r holds nodal forces [N], moments [N m] and TCA rows T_i - F_tca
    /// [N] and tip-constraint rows k_c (c_j . (p_tip - p_target(lambda))) [N] (k_c =
    /// max(EA, GA)/L, c_j the held world directions) and contact rows min(lambda, k g) [N]
    /// with an unchanged contact set since the previous iterate; scale = max(||f_ext||_inf,
    /// max_i c_i |T_i|, ||tip reaction||_inf, max |lambda|) (external nodal loads incl. the
    /// tip moment); floor_i is the
    /// round-off level of the row (Discretization::round_off_floor:
    /// 10 eps nodes max(EA, GA) for force and TCA rows, 10 eps nodes max(EI, GJ)/L plus
    /// that times h for moment rows; constraint rows as force rows).
    kConverged,
    kStepTooSmall,   ///< a load increment halved below Options::min_load_step failed
    kLoadStepLimit,  ///< Options::max_load_steps attempts without reaching lambda = 1
    /// With obstacles: the last failed load step changed the contact set more than
    /// Options::max_contact_changes times and no smaller step reached lambda = 1; the
    /// returned state is that step's last Newton iterate (at its load factor).
    kContactNotSettled,
    kNotRun,  ///< a default-constructed summary: no solve filled it
  };
  Status status = Status::kNotRun;
  bool converged() const { return status == Status::kConverged; }
  int load_steps = 0;      ///< accepted load steps
  int rejected_steps = 0;  ///< failed (halved) load steps
  int iterations = 0;      ///< Newton and chord iterations (linear solves), all steps
  /// ||r||_inf of the returned state at its load factor [N, N m] (+inf when it cannot be
  /// evaluated there).
  double residual_inf = 0.0;
  double residual_scale = 0.0;  ///< scale of the relative tolerance
  /// The residual both methods report (rod::Result::residual, docs/scenario-format.md): at
  /// the returned state and load factor 1, max_i |r_i| / F_c over the force, TCA and
  /// constraint rows and max |r_i| / (L F_c) over the moment rows, F_c =
  /// characteristic_force_N; empty when the residual cannot be evaluated there (or no solve ran).
  std::optional<double> equilibrium_residual;
  double characteristic_force_N = 0.0;  ///< F_c of the solve's loads (rod::characteristic_force_N)
  double load_factor = 0.0;             ///< lambda reached
  double wall_time_s = 0.0;
  std::string message;  ///< why it stopped (empty when converged)
};

/// "converged", "step_too_small", "load_step_limit", "contact_not_settled" or "not_run".
const char* to_string(Summary::Status s);

/// Element-level quantities (for tests): residual and consistent tangent in the
/// element's nodal increments (dp_a, dtheta_a) per node, strings at fixed tensions.
struct ElementEvaluation {
  Eigen::VectorXd residual;                       ///< 6 (order + 1)
  Eigen::MatrixXd tangent;                        ///< d residual / d increments
  std::vector<double> lengths_m;                  ///< element share of each string length
  std::vector<Eigen::VectorXd> length_gradients;  ///< d l_i / d increments
};

/// Strains at a quadrature point (for tests and post-processing).
struct PointStrain {
  double s_m;
  Eigen::Vector3d nu_B;
  Eigen::Vector3d omega_B;
};

/// The loads of one solve on the mesh (Discretization::load_case; the FE dynamics builds its
/// own with make_load_case): the applied loads (rod::Loads::applied, load scale folded in)
/// and their consistent nodal forces, computed once per solve. The one place the FE forms the
/// external load terms and their tangent (subtract).
struct LoadCase {
  rod::Loads loads;  ///< applied loads: drive tensions, TCA segments, tip wrench, gravity
  /// On the free-node dofs (6 per node, forces only), at load factor 1: gravity
  /// (int N_a psi A ds) g at every node and the tip force with the tip mass's weight
  /// (rod::tip_force_with_weight_W_N) at the tip node [N].
  Eigen::VectorXd nodal_force_W_N;
  double tip_mass_kg = 0.0;  ///< the point mass whose weight the tip force includes [kg]

  /// r -= lambda (nodal forces, and the world-frame tip moment M_e as the virtual work
  /// M_e . dtheta_W = (R^T M_e) . dtheta_B, i.e. m(L) = M_e); with `tangent`, its part
  /// d/deta of -exp(-eta) R^T M = -hat(R^T M) at the tip rotation's entries (which must be in
  /// the pattern). `r` holds the free-node rows first.
  void subtract(const State& state, double lambda, Eigen::VectorXd& r,
                Eigen::SparseMatrix<double>* tangent) const;
};

/// A LoadCase of `loads` (validated against `model`, applied) on a mesh whose free node k
/// (k = 1 .. nodes - 1) carries the mass node_mass_kg[k] = int N_k psi A ds [kg] (index 0,
/// the clamped base node, is ignored), with a tip point mass tip_mass_kg.
LoadCase make_load_case(const rod::RodModel& model, const rod::Loads& loads,
                        const std::vector<double>& node_mass_kg, double tip_mass_kg);

/// The discrete problem: mesh, degrees of freedom, residual and tangent. Keeps a pointer to
/// the model (which must outlive it) and caches the tangent's pattern slots (not thread-safe).
/// The model is constant: every load (drive tensions and temperatures, tip wrench, gravity)
/// comes in a LoadCase per call.
class Discretization {
 public:
  /// Validates the options (InputError naming `elements`, `order`, ...).
  Discretization(const rod::RodModel& model, const Options& options);

  /// Elements of the mesh: Options::elements for a uniform body; for a body that varies
  /// along s (docs/scenario-format.md "Profiles along the body") the mesh has a node at every
  /// breakpoint and each piece between breakpoints max(1, round(elements x piece / L)) equal
  /// elements, so the count may differ from Options::elements. Options::extra_knots_m are
  /// breakpoints too.
  int element_count() const { return elements_; }
  /// Reference arc length of element e's first node and its length [m].
  double element_start_m(int e) const { return element_s0_m_[static_cast<std::size_t>(e)]; }
  double element_length_m(int e) const { return element_h_m_[static_cast<std::size_t>(e)]; }
  int order() const { return order_; }
  int node_count() const { return elements_ * order_ + 1; }
  /// Unknowns: 6 per free node (the base node is clamped), then one per TCA actuator, then
  /// the tip reaction components along the held directions (3 pinned, 1 normal-only, 0 free),
  /// then the contact multipliers (State::contact_lambda_N).
  int dof_count() const {
    return 6 * (node_count() - 1) + static_cast<int>(tca_actuators_.size()) + constraint_count() +
           contact_count();
  }
  /// Number of held tip directions: 3 (pinned), 1 (normal-only contact) or 0.
  int constraint_count() const { return static_cast<int>(held_directions_W_.size()); }
  /// Number of contact multipliers: (nodes - 1) x obstacles x candidates (0 without obstacles).
  int contact_count() const { return (node_count() - 1) * contact_pairs_per_node(); }
  /// Contact pairs of one node: obstacles x the section's candidates (rod::section_gaps).
  int contact_pairs_per_node() const {
    return static_cast<int>(model_->obstacles.size()) * contact_candidates_;
  }
  /// Contact candidates of a section (rod::contact_candidate_count of the mesh's outlines).
  int contact_candidates() const { return contact_candidates_; }
  /// The node of contact pair j (State::contact_lambda_N's order).
  int contact_node(int j) const { return j / contact_pairs_per_node() + 1; }
  /// k = max(EA, GA)/L [N/m]: the contact rows k g are forces, as the tip-constraint rows.
  double contact_stiffness_N_m() const { return contact_stiffness_N_m_; }
  /// The contact set of `state`: per (node, obstacle) pair (State::contact_lambda_N's
  /// order), 1 where lambda - k g > 0 (the row k g = 0 holds), 0 where it is open (lambda = 0).
  std::vector<char> contact_set(const State& state) const;
  /// One rod::ContactSample per free node and contact candidate against obstacle o: s, p + c,
  /// lambda n where lambda > 0 (zero otherwise), the gap g.
  std::vector<rod::ContactSample> contact_samples(const State& state, int obstacle) const;
  /// What the clamp applies to the rod (world frame, moment about the base point) at load
  /// factor lambda: the base node's rows of the internal forces of the first element minus
  /// the base node's share of the weight (the clamp's reaction keeps the base node in
  /// equilibrium). Strings are internal forces and are included in the element's rows.
  rod::Wrench base_reaction(const State& state, const LoadCase& loads, double lambda) const;
  /// Prescribed tip position at load factor lambda along the held directions:
  /// p_ref + lambda (p_target - p_ref), p_ref the stress-free tip [m, world].
  Eigen::Vector3d tip_target_W_m(double lambda) const;
  const rod::RodModel& model() const { return *model_; }

  /// The stress-free reference configuration (exact arc of constant omega*), tensions 0.
  State reference_state() const;

  /// Per node, int N_a psi A ds over the mesh by the element's Gauss rule [kg] (the weights
  /// of the consistent gravity loads; exact for a uniform body).
  const std::vector<double>& node_mass_kg() const { return node_mass_kg_; }
  /// make_load_case of `loads` on this mesh (its node masses, the model's tip mass).
  LoadCase load_case(const rod::Loads& loads) const;

  /// The rows of the contact multipliers in `residual`.
  enum class ContactRows {
    kComplementarity,  ///< min(lambda, k g): zero at a solution of the contact problem
    kOpen,  ///< lambda: every pair open (the tangent the solver condenses the contact onto)
  };
  /// Residual at load factor lambda under `loads` (and the tangent when `tangent` is
  /// non-null; its sparsity pattern is the same on every call): internal forces, the TCA rows
  /// at the loads' segment temperatures ramped by lambda (rod::ramp_segments), the tip
  /// constraint, minus LoadCase::subtract, minus the contact forces lambda G with the contact
  /// rows `rows`.
  Eigen::VectorXd residual(const State& state, const LoadCase& loads, double lambda,
                           Eigen::SparseMatrix<double>* tangent = nullptr,
                           ContactRows rows = ContactRows::kComplementarity) const;

  /// Applies an increment dx (dof_count) to a state: p += dp, R <- R exp(dtheta), T += dT,
  /// tip reaction += sum_j c_j dF_j.
  void retract(State& state, const Eigen::VectorXd& dx) const;

  /// One element with string tensions `tensions_N` (per actuator, one string).
  ElementEvaluation element(const State& state, int e, const std::vector<double>& tensions_N) const;

  /// Current length of one string of each actuator [m].
  std::vector<double> string_lengths(const State& state) const;

  /// Centerline pose at reference arc length s_m in [0, L] (beam_fe/probes.cpp): a node's own
  /// pose, else the interpolation of the element holding s (p = sum N_a p_a, R = R_r exp(sum
  /// N_a psi_a)), exact for the discrete solution.
  void pose_at(const State& state, double s_m, Eigen::Vector3d& p_W_m, Eigen::Matrix3d& R_WB) const;

  /// Strains at every quadrature point.
  std::vector<PointStrain> strains(const State& state) const;

  /// Scale of the relative tolerance at lambda: max(||f_ext||_inf, max_i c_i |T_i|, the tip
  /// reaction's and the contact multipliers' largest magnitude).
  double residual_scale(const State& state, const LoadCase& loads, double lambda) const;

  /// Round-off level of the residual rows: force rows (and TCA rows) [N], moment rows [N m].
  struct Floor {
    double force, moment;
  };
  /// force = 10 eps nodes max(EA, GA); moment = 10 eps nodes max(EI, GJ)/L + force h. A
  /// stiffness the caller adds to the strains' (the dynamics' viscous c_e B: its stresses are
  /// formed from the same strain differences) enters with the elastic one: max(EA, GA) +
  /// added_se [N], max(EI, GJ) + added_bt [N m^2].
  Floor round_off_floor(double added_se_N = 0.0, double added_bt_Nm2 = 0.0) const;

  /// The convergence test of Summary::Status::kConverged, row by row.
  bool within_tolerance(const Eigen::VectorXd& r, const State& state, const LoadCase& loads,
                        double lambda, const Options& options) const;

  /// The increment dx with retract(b, dx) = a (positions, rotation logarithms, TCA tensions,
  /// reaction components): used to extrapolate converged load steps.
  Eigen::VectorXd difference(const State& a, const State& b) const;

  /// Constant-strain predictor at load factor lambda: the exact solution of straight strings
  /// at constant offsets without gravity, tip loads or tip constraint (conventions.md closed
  /// form, with TCA tensions from a small Newton solve of T_i = F_tca(delta_i(T))). Gravity,
  /// tip loads and the tip constraint are ignored (it is a starting guess; the reaction is 0).
  /// False, with `state` untouched, without actuators (the guess would be the reference),
  /// for helical routing, or when the TCA law cannot be evaluated.
  bool constant_strain_guess(const LoadCase& loads, double lambda, State& state) const;

  /// Sets the tensions of tension drives to lambda times their value in `loads`.
  void apply_prescribed_tensions(const LoadCase& loads, State& state, double lambda) const;

  /// Contact pair j (State::contact_lambda_N's order) at `state`: the gap g [m] and the
  /// generalized direction G = (n, R^T (c x n)) of its force on the node's dofs (force rows
  /// world, moment rows in the node's material frame; the force is lambda G). With `dG`,
  /// `dg`: their derivatives in the node's increments (dp, dtheta material, as retract), by
  /// central differences of rod::section_gaps (steps 1e-7 L and 1e-5 rad); where the
  /// candidate does not exist on both sides of a step (g = +infinity: a rectangle's edge
  /// candidate) dg is the first variation n . dp + (c x n) . dtheta_W and dG is zero. A
  /// candidate that does not exist has g = +infinity and G = 0.
  struct ContactPair {
    double gap_m = 0.0;
    Eigen::Matrix<double, 6, 1> G = Eigen::Matrix<double, 6, 1>::Zero();
    rod::SectionGap section;  ///< g, n, c of rod::section_gap
  };
  ContactPair contact_pair(const State& state, int j, Eigen::Matrix<double, 6, 6>* dG = nullptr,
                           Eigen::Matrix<double, 1, 6>* dg = nullptr) const;
  /// The pairs of node k against obstacle o, every candidate of the section at once (as
  /// contact_pair for each; rod::section_gaps evaluates them together, so a loop over a
  /// node's pairs costs one evaluation per difference step instead of one per candidate).
  struct ContactBlock {
    std::vector<ContactPair> pair;
    std::vector<Eigen::Matrix<double, 6, 6>> dG;  ///< with derivatives only
    std::vector<Eigen::Matrix<double, 1, 6>> dg;  ///< with derivatives only
  };
  void contact_block(const State& state, int k, int obstacle, bool derivatives,
                     ContactBlock& out) const;

 private:
  struct Quadrature {
    std::vector<double> xi, weight;
  };
  const rod::RodModel* model_;
  int elements_, order_;
  double h_m_;
  std::vector<double> element_s0_m_, element_h_m_;  // per element: first node's s, length
  Quadrature quad_;
  std::vector<int> tca_actuators_;                  // actuator index of each TCA unknown
  std::vector<int> tca_unknown_;                    // per actuator: its TCA unknown or -1
  std::vector<double> node_mass_kg_;                // per node int N_a psi A ds (element rule)
  std::vector<Eigen::Vector3d> held_directions_W_;  // tip constraint: unit world directions c_j
  Eigen::Vector3d tip_reference_W_m_ = Eigen::Vector3d::Zero();  // stress-free tip position
  Eigen::Vector3d tip_goal_W_m_ = Eigen::Vector3d::Zero();       // tip_constraint.position
  double constraint_stiffness_N_m_ = 0.0;      // k_c = max(EA, GA)/L: constraint rows in N
  double contact_stiffness_N_m_ = 0.0;         // k = max(EA, GA)/L: contact rows in N
  std::vector<rod::ContactOutline> outlines_;  // per node: its section's contact outline
  int contact_candidates_ = 0;  // contact candidates per section (rod::contact_candidate_count)
  // K_nu, K_omega and omega* at s = 0: a uniform body's at every s, evaluated once.
  rod::SectionStiffness base_stiffness_;
  Eigen::Vector3d base_omega_star_ = Eigen::Vector3d::Zero();

  /// Builds the tangent's pattern and the position of every element entry in its values.
  void assemble_pattern(Eigen::SparseMatrix<double>& K) const;
  void evaluate_element(const State& state, int e, const std::vector<double>& tensions_N,
                        bool with_tangent, ElementEvaluation& out) const;
  mutable std::vector<int> element_slots_;  // per element, (6 n)^2 value indices or -1
  mutable std::vector<int> tca_slots_;  // per TCA unknown: row then column entries, then diagonal
  mutable std::vector<int> constraint_slots_;  // per held direction: 3 row, then 3 column entries
  // Per contact pair: 6 row entries (k g row), 6 column entries (lambda column), diagonal.
  mutable std::vector<int> contact_slots_;
  // Per free node k: the 36 entries of its diagonal block (row-major), for contact tangents.
  mutable std::vector<int> node_block_slots_;
};

/// The model's probes on `state` (Discretization::pose_at at each probe's s).
std::vector<rod::ProbeResult> probe_results(const Discretization& disc, const State& state);

/// The FE static solver of one model, with the call shape of cosserat::ShootingSolver: built
/// once (validates the options: InputError naming the field; meshes the body), then
/// solve(loads, state) per load case and make_result. Holds a reference to the model, which
/// must outlive it; not thread-safe (one per thread), cheap to reuse across the points of a
/// sweep.
class Solver {
 public:
  Solver(const rod::RodModel& model, const Options& options);
  /// Solves under `loads` from `state` (beam_fe::solve below says how).
  Summary solve(const rod::Loads& loads, State& state) const;
  /// The result file record of `state` (beam_fe::make_result below).
  rod::Result make_result(const rod::Loads& loads, const State& state,
                          const Summary& summary) const;
  const Discretization& discretization() const { return disc_; }
  const Options& options() const { return options_; }

 private:
  const rod::RodModel* model_;
  Options options_;
  Discretization disc_;
};

/// Solves the model from `state` (warm start if it matches the mesh, else from the
/// reference configuration), ramping loads and actuation with a load factor lambda = 0 -> 1
/// in adaptive steps (halve on failure, double after convergence within 4 iterations):
/// gravity, tip wrench and tension drives scale with lambda; TCA temperatures ramp from the
/// material's reference temperature to their targets; a tip_constraint's target moves from the
/// stress-free tip p_ref to p_ref + lambda (p_target - p_ref) (along the normal for a contact).
/// A step from the unloaded state starts from the constant-strain predictor
/// (constant_strain_guess); later steps from the secant extrapolation of the last two accepted
/// states (a failed predicted start is retried from the last accepted state). Each step runs Newton
/// with full steps (backtracking only out of the model's domain); once the residual contracts by
/// 1e-2 per iteration the last factorization is reused (chord steps) until the contraction
/// degrades. KLU pivots once and then refactorizes with that pivot order while its condition
/// estimate holds. With obstacles the contact is not ramped (the obstacles are always there):
/// each Newton iteration solves the linearized contact problem exactly, without chord steps,
/// and the multipliers of a warm start (State::contact_lambda_N) start its contact set.
/// Throws InputError for bad options; never throws for non-convergence: `state` then holds the
/// last accepted configuration (for kContactNotSettled, the last iterate of the failed step).
///
/// `loads` replace the model's own (drive tensions and temperatures, tip wrench, gravity;
/// loads.applied(model) with its load scale; InputError naming the field when they do not fit
/// the model). A state converged at load factor 1 (for any loads, on the same mesh) is a warm
/// start: one Newton solve at the new loads, and the ramp from the reference configuration
/// only if that fails. This is how a sweep runs on the FE: one State across its points.
Summary solve(const rod::RodModel& model, const rod::Loads& loads, const Options& options,
              State& state);
/// Solves the model's own loads: solve(model, rod::Loads::from_model(model), options, state).
Summary solve(const rod::RodModel& model, const Options& options, State& state);

/// Fills a result file record: method "fe", discretization {elements, order}, tip pose,
/// actuator tensions and elongations (coil contact at the segments of `loads`), three-point
/// bending radius, centerline at nodes, the base reaction (Discretization::base_reaction at
/// the state's load factor) and, per obstacle, rod::summarize_contact of the contact samples
/// (Discretization::contact_samples) about the base point.
rod::Result make_result(const rod::RodModel& model, const rod::Loads& loads, const Options& options,
                        const State& state, const Summary& summary);
/// make_result with the model's own loads.
rod::Result make_result(const rod::RodModel& model, const Options& options, const State& state,
                        const Summary& summary);

/// Parses "reduced"/"full" (InputError naming `integration` otherwise).
Integration parse_integration(const std::string& text);
/// Parses "klu"/"umfpack"/"sparselu" (InputError naming `linear_solver` otherwise) and loads
/// the back end it names (load_linear_solver), so a missing plugin is reported here.
LinearSolver parse_linear_solver(const std::string& text);

/// Folders searched for the UMFPACK plugin libtcasim_umfpack.so, in order:
///  1. the environment variable TCASIM_PLUGIN_DIR, when set and non-empty (then the only one);
///  2. the installed plugin folder relative to the program or shared library holding this
///     code: <its folder>/../lib/tcasim for a program in <prefix>/bin (and the build tree's
///     bin/), <its folder>/tcasim for a library in <prefix>/lib (the relative paths the build
///     was configured with);
///  3. <CMAKE_INSTALL_PREFIX>/lib/tcasim of the configured install prefix;
///  4. the build tree's lib/tcasim (a test or the Python module run from the build tree).
std::vector<std::string> umfpack_plugin_candidates();

/// Loads the back end of `kind` unless it is built in or already loaded: the UMFPACK plugin
/// from the first candidate folder it loads from (umfpack_plugin_candidates). Thread-safe.
/// InputError `linear_solver = umfpack needs the UMFPACK plugin ...` naming every path tried
/// and the loader's reason when it cannot be loaded.
void load_linear_solver(LinearSolver kind);

}  // namespace tcasim::beam_fe
