// Mesh, degrees of freedom and global assembly of the beam FE problem.
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "beam_fe/beam_fe.hpp"
#include "beam_fe/internal/quadrature.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"
#include "rod/closed_form.hpp"
#include "rod/obstacle.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// The TCA row of one string: phi(T, delta) with coil contact (tca::contact_residual), zero
/// where the tension T and the elongation delta satisfy the TCA law.
tca::ContactResidual tca_row(const rod::Actuator& act, const std::vector<tca::Segment>& targets,
                             double tension_N, double elongation_m, double lambda) {
  std::vector<tca::Segment> segments;
  rod::ramp_segments(act.drive.tca->material(), targets, lambda, segments);
  return tca::contact_residual(*act.drive.tca, tension_N, elongation_m, segments);
}

}  // namespace

LoadCase make_load_case(const rod::RodModel& model, const rod::Loads& loads,
                        const std::vector<double>& node_mass_kg, double tip_mass_kg) {
  loads.validate(model);
  LoadCase c;
  c.loads = loads.applied(model);
  c.tip_mass_kg = tip_mass_kg;
  const int nodes = static_cast<int>(node_mass_kg.size());
  assert(nodes >= 2);
  const Vector3d& g = c.loads.gravity_W_m_s2;
  c.nodal_force_W_N = VectorXd::Zero(6 * (nodes - 1));
  for (int k = 1; k < nodes; ++k) c.nodal_force_W_N.segment<3>(6 * (k - 1)) = node_mass_kg[k] * g;
  // The tip force and the tip mass's weight m g (rod::tip_force_with_weight_W_N).
  c.nodal_force_W_N.segment<3>(6 * (nodes - 2)) +=
      tip_mass_kg == 0.0 ? c.loads.tip_force_W_N
                         : Vector3d(c.loads.tip_force_W_N + tip_mass_kg * g);
  return c;
}

void LoadCase::subtract(const State& state, double lambda, VectorXd& r,
                        Eigen::SparseMatrix<double>* tangent) const {
  const Eigen::Index free_dofs = nodal_force_W_N.size();
  r.head(free_dofs) -= lambda * nodal_force_W_N;
  const Matrix3d R_tip = state.q_WB.back().toRotationMatrix();
  const Vector3d M_B = lambda * R_tip.transpose() * loads.tip_moment_W_Nm;
  const Eigen::Index tip_rot = free_dofs - 3;
  r.segment<3>(tip_rot) -= M_B;
  if (tangent) {
    // d/deta of -exp(-eta) R^T M = -hat(R^T M).
    const Matrix3d Km = -so3::hat(M_B);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) tangent->coeffRef(tip_rot + i, tip_rot + j) += Km(i, j);
  }
}

LoadCase Discretization::load_case(const rod::Loads& loads) const {
  return make_load_case(*model_, loads, node_mass_kg_, model_->tip_mass_kg);
}

Discretization::Discretization(const rod::RodModel& model, const Options& options)
    : model_(&model), elements_(options.elements), order_(options.order) {
  require(options.elements >= 1, "elements", options.elements, "must be >= 1");
  require(options.order == 1 || options.order == 2, "order", options.order, "must be 1 or 2");
  require(options.tolerance_abs >= 0.0, "tolerance_abs", options.tolerance_abs, "must be >= 0");
  require(options.tolerance_rel >= 0.0, "tolerance_rel", options.tolerance_rel, "must be >= 0");
  require(options.max_iterations >= 1, "max_iterations", options.max_iterations, "must be >= 1");
  require(options.max_contact_changes >= 0, "max_contact_changes", options.max_contact_changes,
          "must be >= 0");
  require(options.initial_load_step > 0.0 && options.initial_load_step <= 1.0, "initial_load_step",
          options.initial_load_step, "must be in (0, 1]");
  require(model.length_m > 0.0, "body.length_m", model.length_m, "must be > 0");
  h_m_ = model.length_m / elements_;
  base_stiffness_ = model.stiffness_at(0.0);
  base_omega_star_ = model.reference_curvature_at(0.0);
  std::vector<double> knots = model.interior_knots();
  for (const double s : options.extra_knots_m) {
    require(s > 0.0 && s < model.length_m, "extra_knots_m", s,
            "must lie strictly inside (0, body.length_m)");
    knots.push_back(s);
  }
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  if (model.uniform_body() && knots.empty()) {
    element_h_m_.assign(static_cast<std::size_t>(elements_), h_m_);
    for (int e = 0; e < elements_; ++e) {
      element_s0_m_.push_back(model.length_m * (e * order_) / (elements_ * order_));
    }
  } else {
    // A node at every breakpoint and string anchor; equal elements on each piece, in
    // proportion to its length.
    knots.insert(knots.begin(), 0.0);
    knots.push_back(model.length_m);
    for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
      const double a = knots[k], b = knots[k + 1];
      const int n =
          std::max(1, static_cast<int>(std::lround(options.elements * (b - a) / model.length_m)));
      for (int i = 0; i < n; ++i) {
        element_s0_m_.push_back(i == 0 ? a : a + (b - a) * i / n);
        element_h_m_.push_back((i + 1 == n ? b : a + (b - a) * (i + 1) / n) - element_s0_m_.back());
      }
    }
    elements_ = static_cast<int>(element_h_m_.size());
  }

  // Gauss-Legendre points on [-1, 1].
  const int points = order_ + (options.integration == Integration::kFull ? 1 : 0);
  internal::gauss_rule(points, quad_.xi, quad_.weight);

  tca_unknown_.assign(model.actuators.size(), -1);
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const rod::Actuator& act = model.actuators[i];
    if (act.drive.type != rod::Drive::Type::kTca) continue;
    if (!act.drive.tca) {
      throw InputError(fmt::format("actuators[{}].drive", i), act.drive.tca_id,
                       "a TCA drive needs a resolved TCA");
    }
    tca_unknown_[i] = static_cast<int>(tca_actuators_.size());
    tca_actuators_.push_back(static_cast<int>(i));
  }

  // Weights of the consistent gravity loads, int N_a psi A ds (exact with the element rule
  // on a uniform body: degree order <= 2 p - 1).
  const int nodes = node_count();
  node_mass_kg_.assign(static_cast<std::size_t>(nodes), 0.0);
  const bool uniform = model.uniform_body();
  const double uniform_psi_A = model.mass_per_length_kg_m(0.0);
  for (int e = 0; e < elements_; ++e) {
    for (std::size_t g = 0; g < quad_.xi.size(); ++g) {
      const double xi = quad_.xi[g];
      const double h_e = element_h_m_[static_cast<std::size_t>(e)];
      const double wj = quad_.weight[g] * 0.5 * h_e;
      const double psi_A =
          uniform ? uniform_psi_A
                  : model.mass_per_length_kg_m(element_s0_m_[static_cast<std::size_t>(e)] +
                                               0.5 * (xi + 1.0) * h_e);
      double N[3], dN_dxi[3];
      internal::shape(order_, xi, N, dN_dxi);
      for (int a = 0; a <= order_; ++a) node_mass_kg_[e * order_ + a] += wj * N[a] * psi_A;
    }
  }

  // Tip constraint: held world directions (all three when pinned, the normal for a contact),
  // target ramped from the stress-free tip (exact arc of omega*, as reference_state).
  if (uniform) {
    const Vector3d phi_L = model.length_m * model.reference_curvature_at(0.0);
    tip_reference_W_m_ =
        model.base_position_W_m +
        model.R_WB0 * (model.length_m * so3::left_jacobian(phi_L) * Vector3d::UnitZ());
  } else {
    tip_reference_W_m_ = reference_state().p_W_m.back();
  }
  if (model.tip_constraint) {
    tip_goal_W_m_ = model.tip_constraint->position_W_m;
    if (model.tip_constraint->normal_W) {
      const Vector3d n = *model.tip_constraint->normal_W;
      require(n.allFinite() && n.norm() > 0.0, "tip_constraint.normal", n.norm(),
              "must be non-zero");
      held_directions_W_ = {n.normalized()};
    } else {
      held_directions_W_ = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
    }
    constraint_stiffness_N_m_ = model.shear_extension_stiffness().maxCoeff() / model.length_m;
  }
  if (!model.obstacles.empty()) {
    contact_stiffness_N_m_ = model.shear_extension_stiffness().maxCoeff() / model.length_m;
    // Each node's outline; the tip's from the left (its section at s = L).
    for (int e = 0; e < elements_; ++e) {
      for (int a = e == 0 ? 0 : 1; a <= order_; ++a) {
        const double s = element_s0_m_[static_cast<std::size_t>(e)] +
                         element_h_m_[static_cast<std::size_t>(e)] * a / order_;
        outlines_.push_back(rod::contact_outline_at(
            model, s, e + 1 == elements_ && a == order_ ? rod::Side::kLeft : rod::Side::kRight));
      }
    }
    // The section's shape (and so its outline's kind) is the same at every s.
    contact_candidates_ = rod::contact_candidate_count(outlines_.back().kind);
  }
}

Vector3d Discretization::tip_target_W_m(double lambda) const {
  return tip_reference_W_m_ + lambda * (tip_goal_W_m_ - tip_reference_W_m_);
}

State Discretization::reference_state() const {
  const rod::RodModel& model = *model_;
  State st;
  const int nodes = node_count();
  const Eigen::Quaterniond q0(model.R_WB0);
  if (!model.uniform_body() || !model.interior_knots().empty()) {
    // omega* varies (or the mesh is aligned to string anchors or spline knots): the stress-free
    // shape R' = R hat(omega*(s)), p' = R e3 by constant- curvature arcs at the midpoint
    // curvature of kSubsteps substeps per node interval (second order; only the starting
    // configuration and the constraint ramp's start use it).
    constexpr int kSubsteps = 64;
    Eigen::Quaterniond q = q0;
    Vector3d p = model.base_position_W_m;
    st.s_m.push_back(0.0);
    st.p_W_m.push_back(p);
    st.q_WB.push_back(q);
    for (int e = 0; e < elements_; ++e) {
      const double s0 = element_s0_m_[static_cast<std::size_t>(e)];
      const double h = element_h_m_[static_cast<std::size_t>(e)];
      for (int a = 1; a <= order_; ++a) {
        const double lo = s0 + h * (a - 1) / order_;
        const double hi = a == order_ ? s0 + h : s0 + h * a / order_;
        const double ds = (hi - lo) / kSubsteps;
        for (int j = 0; j < kSubsteps; ++j) {
          const Vector3d phi = ds * model.reference_curvature_at(lo + (j + 0.5) * ds);
          p += q.toRotationMatrix() * (ds * so3::left_jacobian(phi) * Vector3d::UnitZ());
          q = (q * so3::exp_quaternion(phi)).normalized();
        }
        st.s_m.push_back(hi);
        st.p_W_m.push_back(p);
        st.q_WB.push_back(q);
      }
    }
    st.tensions_N.assign(model.actuators.size(), 0.0);
    st.contact_lambda_N.assign(static_cast<std::size_t>(contact_count()), 0.0);
    return st;
  }
  for (int k = 0; k < nodes; ++k) {
    const double s = model.length_m * k / (nodes - 1);
    const Vector3d phi = s * model.reference_curvature_at(0.0);
    st.s_m.push_back(s);
    // Exact arc of constant curvature: R = R0 exp(s omega*), p = p0 + R0 s Jl(s omega*) e3.
    st.p_W_m.push_back(model.base_position_W_m +
                       model.R_WB0 * (s * so3::left_jacobian(phi) * Vector3d::UnitZ()));
    st.q_WB.push_back((q0 * so3::exp_quaternion(phi)).normalized());
  }
  st.tensions_N.assign(model.actuators.size(), 0.0);
  st.contact_lambda_N.assign(static_cast<std::size_t>(contact_count()), 0.0);
  st.tip_reaction_W_N.setZero();
  st.load_factor = 0.0;
  return st;
}

void Discretization::apply_prescribed_tensions(const LoadCase& loads, State& state,
                                               double lambda) const {
  for (std::size_t i = 0; i < model_->actuators.size(); ++i) {
    const rod::Drive& d = model_->actuators[i].drive;
    if (d.type == rod::Drive::Type::kTension)
      state.tensions_N[i] = lambda * loads.loads.actuators[i].tension_N;
  }
}

void Discretization::retract(State& state, const VectorXd& dx) const {
  const int nodes = node_count();
  for (int k = 1; k < nodes; ++k) {
    state.p_W_m[k] += dx.segment<3>(6 * (k - 1));
    state.q_WB[k] =
        (state.q_WB[k] * so3::exp_quaternion(dx.segment<3>(6 * (k - 1) + 3))).normalized();
  }
  for (std::size_t j = 0; j < tca_actuators_.size(); ++j) {
    state.tensions_N[tca_actuators_[j]] += dx[6 * (nodes - 1) + static_cast<int>(j)];
  }
  const int first_constraint = 6 * (nodes - 1) + static_cast<int>(tca_actuators_.size());
  for (int j = 0; j < constraint_count(); ++j) {
    state.tip_reaction_W_N += dx[first_constraint + j] * held_directions_W_[j];
  }
  const int first_contact = first_constraint + constraint_count();
  for (int j = 0; j < contact_count(); ++j) state.contact_lambda_N[j] += dx[first_contact + j];
}

VectorXd Discretization::difference(const State& a, const State& b) const {
  const int nodes = node_count();
  VectorXd dx = VectorXd::Zero(dof_count());
  for (int k = 1; k < nodes; ++k) {
    dx.segment<3>(6 * (k - 1)) = a.p_W_m[k] - b.p_W_m[k];
    dx.segment<3>(6 * (k - 1) + 3) = so3::log(b.q_WB[k].conjugate() * a.q_WB[k]);
  }
  for (std::size_t j = 0; j < tca_actuators_.size(); ++j) {
    dx[6 * (nodes - 1) + static_cast<int>(j)] =
        a.tensions_N[tca_actuators_[j]] - b.tensions_N[tca_actuators_[j]];
  }
  const int first_constraint = 6 * (nodes - 1) + static_cast<int>(tca_actuators_.size());
  for (int j = 0; j < constraint_count(); ++j) {
    dx[first_constraint + j] = held_directions_W_[j].dot(a.tip_reaction_W_N - b.tip_reaction_W_N);
  }
  const int first_contact = first_constraint + constraint_count();
  for (int j = 0; j < contact_count(); ++j)
    dx[first_contact + j] = a.contact_lambda_N[j] - b.contact_lambda_N[j];
  return dx;
}

bool Discretization::constant_strain_guess(const LoadCase& loads, double lambda,
                                           State& state) const {
  const rod::RodModel& model = *model_;
  const std::size_t n_act = model.actuators.size();
  if (n_act == 0) return false;  // the guess would be the reference configuration itself
  for (const rod::Actuator& a : model.actuators) {
    // The closed form has strings from base to tip.
    if (a.routing.type != rod::Routing::Type::kStraight || a.anchored_inside(model.length_m))
      return false;
  }
  // The closed form (rod/closed_form.hpp) of the tension drives, with the TCA tensions
  // solving phi_i(T_i, delta_i(T)) = 0 (the TCA law with coil contact) at its elongations
  // delta_i = L |nu + omega x r_i| - rest_i (exact for constant strains and straight strings).
  std::vector<double> T(n_act, 0.0), cT(n_act, 0.0);
  for (std::size_t i = 0; i < n_act; ++i) {
    if (model.actuators[i].drive.type == rod::Drive::Type::kTension)
      T[i] = lambda * loads.loads.actuators[i].tension_N;
    cT[i] = model.actuators[i].count * T[i];
  }
  const std::size_t k = tca_actuators_.size();
  if (k > 0) {
    std::vector<std::vector<tca::Segment>> segments(n_act);
    for (const int i : tca_actuators_) {
      const rod::Actuator& act = model.actuators[i];
      rod::ramp_segments(act.drive.tca->material(), loads.loads.actuators[i].segments, lambda,
                         segments[i]);
    }
    rod::GuessTensionOptions options;
    options.tolerance_rel = 1e-13;  // far below the FE's own tolerance
    Eigen::VectorXd T_tca = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(k));
    if (!rod::solve_guess_tensions(model, tca_actuators_, segments,
                                   Eigen::Matrix<double, 6, 1>::Zero(), options, cT, T_tca)) {
      return false;
    }
    for (std::size_t a = 0; a < k; ++a) T[tca_actuators_[a]] = T_tca[static_cast<Eigen::Index>(a)];
  }
  const rod::ConstantStrains cf = rod::closed_form_strains(model, cT);
  const Vector3d nu = Vector3d::UnitZ() + cf.e, omega = cf.omega;
  if (!nu.allFinite() || !omega.allFinite()) return false;
  State st = reference_state();
  const Eigen::Quaterniond q0(model.R_WB0);
  for (std::size_t n = 0; n < st.s_m.size(); ++n) {
    const double s = st.s_m[n];
    // Constant strains: R = R0 exp(s omega), p = p0 + R0 s Jl(s omega) nu.
    st.p_W_m[n] = model.base_position_W_m + model.R_WB0 * (s * so3::left_jacobian(s * omega) * nu);
    st.q_WB[n] = (q0 * so3::exp_quaternion(s * omega)).normalized();
  }
  st.tensions_N = T;
  st.load_factor = state.load_factor;
  state = std::move(st);
  return true;
}

double Discretization::residual_scale(const State& state, const LoadCase& loads,
                                      double lambda) const {
  double scale = lambda * loads.nodal_force_W_N.cwiseAbs().maxCoeff();
  scale = std::max(scale, lambda * loads.loads.tip_moment_W_Nm.cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i < model_->actuators.size(); ++i) {
    scale = std::max(scale, model_->actuators[i].count * std::abs(state.tensions_N[i]));
  }
  if (constraint_count() > 0) scale = std::max(scale, state.tip_reaction_W_N.cwiseAbs().maxCoeff());
  for (const double lambda_N : state.contact_lambda_N) scale = std::max(scale, std::abs(lambda_N));
  return scale;
}

Discretization::Floor Discretization::round_off_floor(double added_se_N,
                                                      double added_bt_Nm2) const {
  // Strains are differences of nodal values divided by the node spacing L/(nodes - 1), so
  // they carry round-off ~eps (nodes - 1); times the stiffness and a factor 10 for the
  // sums, that is the level below which the assembled residual cannot be resolved
  // (measured: force rows ~0.06, moment rows ~0.02 of these bounds). Moment rows also pick
  // up the force round-off times the node spacing h.
  constexpr double kRoundOffTerms = 10.0;
  const double eps_n = kRoundOffTerms * std::numeric_limits<double>::epsilon() * node_count();
  double K_se = model_->shear_extension_stiffness().maxCoeff();
  double K_bt = model_->bending_torsion_stiffness().maxCoeff();
  for (int e = 0; e < elements_ && !model_->uniform_body(); ++e) {
    // The stiffest point of a varying body: its largest values lie at element ends.
    for (const rod::Side side : {rod::Side::kLeft, rod::Side::kRight}) {
      for (const double s : {element_s0_m_[e], element_s0_m_[e] + element_h_m_[e]}) {
        K_se = std::max(K_se, model_->shear_extension_stiffness(s, side).maxCoeff());
        K_bt = std::max(K_bt, model_->bending_torsion_stiffness(s, side).maxCoeff());
      }
    }
  }
  const double force = eps_n * (K_se + added_se_N);
  const double moment = eps_n * (K_bt + added_bt_Nm2) / model_->length_m +
                        force * model_->length_m / (node_count() - 1);
  return {force, moment};
}

bool Discretization::within_tolerance(const VectorXd& r, const State& state, const LoadCase& loads,
                                      double lambda, const Options& options) const {
  const double base =
      options.tolerance_abs + options.tolerance_rel * residual_scale(state, loads, lambda);
  const Floor floor = round_off_floor();
  const int free_dofs = 6 * (node_count() - 1);
  for (int i = 0; i < r.size(); ++i) {
    const bool moment_row = i < free_dofs && i % 6 >= 3;
    if (!(std::abs(r[i]) <= base + (moment_row ? floor.moment : floor.force))) return false;
  }
  return true;
}

namespace {
/// Index of entry (i, j) in the values of a compressed column-major matrix.
[[maybe_unused]] int slot(const Eigen::SparseMatrix<double>& K, int i, int j) {
  const int* inner = K.innerIndexPtr();
  const int* begin = inner + K.outerIndexPtr()[j];
  const int* end = inner + K.outerIndexPtr()[j + 1];
  const int* it = std::lower_bound(begin, end, i);
  assert(it != end && *it == i);
  return static_cast<int>(it - inner);
}
}  // namespace

void Discretization::assemble_pattern(Eigen::SparseMatrix<double>& K) const {
  // Built directly in compressed column form: the rows of a free node's column are the dofs
  // of the contiguous node range of the elements containing it, then every TCA row, then
  // (tip position columns) the constraint rows, then the node's contact rows. A TCA column
  // holds all free and TCA rows; a constraint column the tip position rows; a contact column
  // its node's rows and its own diagonal. Every slot follows by arithmetic.
  const int n = dof_count();
  const int nodes = node_count();
  const int free_dofs = 6 * (nodes - 1);
  const int n_tca = static_cast<int>(tca_actuators_.size());
  const int tca_end = free_dofs + n_tca;
  const int contact_begin = tca_end + constraint_count();
  const int per_node = contact_pairs_per_node();
  const int tip_pos = free_dofs - 6;
  std::vector<int> first_row(free_dofs), range_rows(free_dofs);
  std::vector<int> outer(n + 1, 0);
  for (int j = 0; j < n; ++j) {
    int count;
    if (j < free_dofs) {
      const int k = j / 6 + 1;  // node of this column
      const int e_first = (k - 1) / order_, e_last = std::min(elements_ - 1, k / order_);
      const int lo = std::max(e_first * order_, 1), hi = (e_last + 1) * order_;
      first_row[j] = 6 * (lo - 1);
      range_rows[j] = 6 * (hi - lo + 1);
      count = range_rows[j] + n_tca + (j >= tip_pos && j < tip_pos + 3 ? constraint_count() : 0) +
              per_node;
    } else if (j < tca_end) {
      count = tca_end;
    } else if (j < contact_begin) {
      count = 3;
    } else {
      count = 7;
    }
    outer[j + 1] = outer[j] + count;
  }
  K.resize(n, n);
  K.resizeNonZeros(outer[n]);
  std::copy(outer.begin(), outer.end(), K.outerIndexPtr());
  int* inner = K.innerIndexPtr();
  for (int j = 0; j < n; ++j) {
    int* it = inner + outer[j];
    if (j < free_dofs) {
      for (int i = 0; i < range_rows[j]; ++i) *it++ = first_row[j] + i;
      for (int t = free_dofs; t < tca_end; ++t) *it++ = t;
      if (j >= tip_pos && j < tip_pos + 3) {
        for (int c = tca_end; c < contact_begin; ++c) *it++ = c;
      }
      for (int o = 0; o < per_node; ++o) *it++ = contact_begin + (j / 6) * per_node + o;
    } else if (j < tca_end) {
      for (int i = 0; i < tca_end; ++i) *it++ = i;
    } else if (j < contact_begin) {
      for (int i = 0; i < 3; ++i) *it++ = tip_pos + i;
    } else {
      const int node_row = 6 * ((j - contact_begin) / per_node);
      for (int i = 0; i < 6; ++i) *it++ = node_row + i;
      *it++ = j;
    }
  }
  std::fill(K.valuePtr(), K.valuePtr() + outer[n], 0.0);
  assert(K.isCompressed());

  const int nd = 6 * (order_ + 1);
  element_slots_.assign(static_cast<std::size_t>(elements_) * nd * nd, -1);
  for (int e = 0; e < elements_; ++e) {
    for (int j = 0; j < nd; ++j) {
      const int gj = 6 * (e * order_) + j - 6;
      if (gj < 0) continue;
      for (int i = 0; i < nd; ++i) {
        const int gi = 6 * (e * order_) + i - 6;
        if (gi < 0) continue;
        assert(gi >= first_row[gj] && gi < first_row[gj] + range_rows[gj]);
        element_slots_[(static_cast<std::size_t>(e) * nd + i) * nd + j] =
            outer[gj] + gi - first_row[gj];
      }
    }
  }
  tca_slots_.clear();
  for (int t = free_dofs; t < tca_end; ++t) {
    for (int k = 0; k < free_dofs; ++k)
      tca_slots_.push_back(outer[k] + range_rows[k] + (t - free_dofs));
    for (int k = 0; k < free_dofs; ++k) tca_slots_.push_back(outer[t] + k);
    tca_slots_.push_back(outer[t] + t);
  }
  constraint_slots_.clear();
  for (int c = tca_end; c < contact_begin; ++c) {
    for (int i = 0; i < 3; ++i)
      constraint_slots_.push_back(outer[tip_pos + i] + range_rows[tip_pos + i] + n_tca +
                                  (c - tca_end));
    for (int i = 0; i < 3; ++i) constraint_slots_.push_back(outer[c] + i);
  }
  contact_slots_.clear();
  node_block_slots_.clear();
  if (per_node > 0) {
    for (int c = contact_begin; c < n; ++c) {
      const int node_col = 6 * ((c - contact_begin) / per_node);
      const int o = (c - contact_begin) % per_node;
      for (int i = 0; i < 6; ++i) {
        const int j = node_col + i;  // the k g row's entry in the node's column j
        const int held = j >= tip_pos && j < tip_pos + 3 ? constraint_count() : 0;
        contact_slots_.push_back(outer[j] + range_rows[j] + n_tca + held + o);
      }
      for (int i = 0; i < 7; ++i) contact_slots_.push_back(outer[c] + i);
    }
    for (int k = 1; k < nodes; ++k) {
      for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
          const int gi = 6 * (k - 1) + i, gj = 6 * (k - 1) + j;
          node_block_slots_.push_back(outer[gj] + gi - first_row[gj]);
        }
      }
    }
  }
#ifndef NDEBUG
  for (int e = 0; e < elements_; ++e)
    for (int i = 0; i < nd; ++i)
      for (int j = 0; j < nd; ++j) {
        const int gi = 6 * (e * order_) + i - 6, gj = 6 * (e * order_) + j - 6;
        if (gi >= 0 && gj >= 0)
          assert(element_slots_[(static_cast<std::size_t>(e) * nd + i) * nd + j] ==
                 slot(K, gi, gj));
      }
  for (int c = tca_end; c < contact_begin; ++c)
    for (int i = 0; i < 3; ++i) {
      assert(constraint_slots_[6 * (c - tca_end) + i] == slot(K, c, tip_pos + i));
      assert(constraint_slots_[6 * (c - tca_end) + 3 + i] == slot(K, tip_pos + i, c));
    }
  for (int c = contact_begin; c < n; ++c) {
    const int node_col = 6 * ((c - contact_begin) / per_node);
    const int* cs = &contact_slots_[13 * static_cast<std::size_t>(c - contact_begin)];
    for (int i = 0; i < 6; ++i) {
      assert(cs[i] == slot(K, c, node_col + i));
      assert(cs[6 + i] == slot(K, node_col + i, c));
    }
    assert(cs[12] == slot(K, c, c));
  }
  for (int k = 1; k < nodes && per_node > 0; ++k)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        assert(node_block_slots_[36 * (k - 1) + 6 * i + j] ==
               slot(K, 6 * (k - 1) + i, 6 * (k - 1) + j));
#endif
}

VectorXd Discretization::residual(const State& state, const LoadCase& loads, double lambda,
                                  Eigen::SparseMatrix<double>* tangent, ContactRows rows) const {
  const rod::RodModel& model = *model_;
  const int n = dof_count();
  const int nodes = node_count();
  const int free_dofs = 6 * (nodes - 1);
  const int nd = 6 * (order_ + 1);
  VectorXd r = VectorXd::Zero(n);
  double* values = nullptr;
  if (tangent) {
    if (tangent->rows() != n || tangent->nonZeros() == 0 || element_slots_.empty())
      assemble_pattern(*tangent);
    values = tangent->valuePtr();
    std::fill(values, values + tangent->nonZeros(), 0.0);
  }
  const std::size_t n_act = model.actuators.size();
  std::vector<double> lengths(n_act, 0.0);
  std::vector<VectorXd> dl(n_act, VectorXd::Zero(free_dofs));
  ElementEvaluation ev;
  for (int e = 0; e < elements_; ++e) {
    evaluate_element(state, e, state.tensions_N, tangent != nullptr, ev);
    const int base = 6 * (e * order_) - 6;
    for (int i = 0; i < nd; ++i) {
      const int gi = base + i;
      if (gi < 0) continue;
      r[gi] += ev.residual[i];
      for (std::size_t a = 0; a < n_act; ++a) dl[a][gi] += ev.length_gradients[a][i];
    }
    if (tangent) {
      const int* slots = &element_slots_[static_cast<std::size_t>(e) * nd * nd];
      for (int i = 0; i < nd; ++i)
        for (int j = 0; j < nd; ++j)
          if (slots[i * nd + j] >= 0) values[slots[i * nd + j]] += ev.tangent(i, j);
    }
    for (std::size_t a = 0; a < n_act; ++a) lengths[a] += ev.lengths_m[a];
  }
  // External loads: dead nodal forces and the world-frame tip moment.
  loads.subtract(state, lambda, r, tangent);
  // TCA rows: phi_i(T_i, l_i - rest_i) (tca::contact_residual: T_i - F_tca with coil
  // contact); columns: c_i dl_i/dq.
  const std::size_t stride = 2 * static_cast<std::size_t>(free_dofs) + 1;
  for (std::size_t j = 0; j < tca_actuators_.size(); ++j) {
    const int a = tca_actuators_[j];
    const rod::Actuator& act = model.actuators[a];
    const int row = free_dofs + static_cast<int>(j);
    const tca::ContactResidual f =
        tca_row(act, loads.loads.actuators[a].segments, state.tensions_N[a],
                lengths[a] - act.rest_length_m, lambda);
    r[row] = f.phi_N;
    if (!tangent) continue;
    const int* slots = &tca_slots_[j * stride];
    for (int k = 0; k < free_dofs; ++k) {
      values[slots[k]] += f.dphi_ddelta_N_m * dl[a][k];
      values[slots[free_dofs + k]] += act.count * dl[a][k];
    }
    values[slots[2 * free_dofs]] += f.dphi_dF;
  }
  // Tip constraint (Lagrange multipliers = reaction components F_j along c_j): the holder's
  // force F = sum_j F_j c_j acts on the tip node (r = internal - external - F), and each
  // held direction gets the row k_c c_j . (p_tip - p_ref - lambda (p_target - p_ref)).
  const int tip_pos = free_dofs - 6;
  const int first_constraint = free_dofs + static_cast<int>(tca_actuators_.size());
  if (constraint_count() > 0) {
    r.segment<3>(tip_pos) -= state.tip_reaction_W_N;
    const Vector3d gap = state.p_W_m.back() - tip_target_W_m(lambda);
    for (int j = 0; j < constraint_count(); ++j) {
      const Vector3d& c = held_directions_W_[j];
      r[first_constraint + j] = constraint_stiffness_N_m_ * c.dot(gap);
      if (!tangent) continue;
      const int* slots = &constraint_slots_[6 * static_cast<std::size_t>(j)];
      for (int i = 0; i < 3; ++i) {
        values[slots[i]] += constraint_stiffness_N_m_ * c[i];
        values[slots[3 + i]] -= c[i];
      }
    }
  }
  // Contact (docs/conventions.md "Contact in the FE"): pair j of node k and obstacle o has
  // the multiplier lambda_j; its force lambda_j G_j (G = (n, R^T (c x n))) acts on node k
  // (r = internal - external - contact), and its row is the complementarity function
  // min(lambda, k g): k g where lambda - k g > 0 (active), lambda elsewhere, with its
  // generalized derivative as tangent; or (kOpen) lambda for every pair.
  const int first_contact = first_constraint + constraint_count();
  ContactBlock block;
  for (int j = 0; j < contact_count(); ++j) {
    const int k = contact_node(j);
    const int in_node = j % contact_pairs_per_node();
    const auto c = static_cast<std::size_t>(in_node % contact_candidates_);
    if (c == 0) {
      // The tangent needs a block's derivatives only where a pair pushes or is held on the
      // surface: most nodes are clear of the obstacles.
      contact_block(state, k, in_node / contact_candidates_, false, block);
      bool needed = false;
      for (std::size_t i = 0; tangent && i < block.pair.size(); ++i) {
        const double lambda_i = state.contact_lambda_N[static_cast<std::size_t>(j) + i];
        needed = needed || lambda_i != 0.0 ||
                 (rows == ContactRows::kComplementarity &&
                  lambda_i - contact_stiffness_N_m_ * block.pair[i].gap_m > 0.0);
      }
      if (needed) contact_block(state, k, in_node / contact_candidates_, true, block);
    }
    const double lambda_N = state.contact_lambda_N[static_cast<std::size_t>(j)];
    const ContactPair& pair = block.pair[c];
    const double kg = contact_stiffness_N_m_ * pair.gap_m;
    const bool active = rows == ContactRows::kComplementarity && lambda_N - kg > 0.0;
    const int node = 6 * (k - 1);
    r.segment<6>(node) -= lambda_N * pair.G;
    r[first_contact + j] = active ? kg : lambda_N;
    if (!tangent) continue;
    const int* cs = &contact_slots_[13 * static_cast<std::size_t>(j)];
    for (int i = 0; i < 6; ++i) {
      if (active) values[cs[i]] += contact_stiffness_N_m_ * block.dg[c][i];
      values[cs[6 + i]] -= pair.G[i];
    }
    if (!active) values[cs[12]] += 1.0;
    if (lambda_N != 0.0) {
      const int* bs = &node_block_slots_[36 * static_cast<std::size_t>(k - 1)];
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) values[bs[6 * a + b]] -= lambda_N * block.dG[c](a, b);
    }
  }
  return r;
}

Discretization::ContactPair Discretization::contact_pair(const State& state, int j,
                                                         Eigen::Matrix<double, 6, 6>* dG,
                                                         Eigen::Matrix<double, 1, 6>* dg) const {
  const int in_node = j % contact_pairs_per_node();
  const bool derivatives = dG != nullptr || dg != nullptr;
  ContactBlock block;
  contact_block(state, contact_node(j), in_node / contact_candidates_, derivatives, block);
  const std::size_t c = static_cast<std::size_t>(in_node % contact_candidates_);
  if (dG) *dG = block.dG[c];
  if (dg) *dg = block.dg[c];
  return block.pair[c];
}

void Discretization::contact_block(const State& state, int node, int obstacle, bool derivatives,
                                   ContactBlock& out) const {
  const rod::Obstacle& obs = model_->obstacles[static_cast<std::size_t>(obstacle)];
  const rod::ContactOutline& outline = outlines_[static_cast<std::size_t>(node)];
  const auto n_cand = static_cast<std::size_t>(contact_candidates_);
  std::vector<rod::SectionGap> gaps;
  auto evaluate = [&](const Vector3d& p, const Matrix3d& R, std::vector<ContactPair>& pairs) {
    gaps = rod::section_gaps(obs, outline, p, R);
    pairs.assign(n_cand, ContactPair());
    for (std::size_t c = 0; c < n_cand; ++c) {
      ContactPair& pc = pairs[c];
      pc.section = gaps[c];
      pc.gap_m = pc.section.gap_m;
      if (std::isfinite(pc.gap_m)) {
        pc.G.head<3>() = pc.section.normal_W;
        pc.G.tail<3>() = R.transpose() * pc.section.offset_W_m.cross(pc.section.normal_W);
      }
    }
  };
  const Vector3d& p = state.p_W_m[static_cast<std::size_t>(node)];
  const Matrix3d R = state.q_WB[static_cast<std::size_t>(node)].toRotationMatrix();
  evaluate(p, R, out.pair);
  out.dG.clear();
  out.dg.clear();
  if (!derivatives) return;
  out.dG.assign(n_cand, Eigen::Matrix<double, 6, 6>::Zero());
  out.dg.assign(n_cand, Eigen::Matrix<double, 1, 6>::Zero());
  // Central differences over the node's increments (dp world, dtheta material: R exp(dtheta)).
  // Steps: 1e-7 L in position and 1e-5 rad in rotation keep the truncation error (step /
  // curvature radius of the obstacle or outline)^2 and the round-off eps |p| / step both
  // near 1e-8 of the derivatives for section and obstacle sizes down to ~1e-3 L.
  const double dp = 1e-7 * model_->length_m, dth = 1e-5;
  // A candidate at the edge of its existence (not finite on a side of a step): its first
  // variation, no force tangent.
  std::vector<char> edge(n_cand, 0);
  std::vector<ContactPair> plus, minus;
  for (int i = 0; i < 6; ++i) {
    Vector3d p_plus = p, p_minus = p;
    Matrix3d R_plus = R, R_minus = R;
    double step;
    if (i < 3) {
      step = dp;
      p_plus[i] += dp;
      p_minus[i] -= dp;
    } else {
      step = dth;
      R_plus = R * so3::exp(dth * Vector3d::Unit(i - 3));
      R_minus = R * so3::exp(-dth * Vector3d::Unit(i - 3));
    }
    evaluate(p_plus, R_plus, plus);
    evaluate(p_minus, R_minus, minus);
    for (std::size_t c = 0; c < n_cand; ++c) {
      if (edge[c] || !std::isfinite(out.pair[c].gap_m)) continue;
      if (!std::isfinite(plus[c].gap_m) || !std::isfinite(minus[c].gap_m)) {
        edge[c] = 1;
        continue;
      }
      out.dG[c].col(i) = (plus[c].G - minus[c].G) / (2.0 * step);
      out.dg[c][i] = (plus[c].gap_m - minus[c].gap_m) / (2.0 * step);
    }
  }
  for (std::size_t c = 0; c < n_cand; ++c) {
    if (!edge[c]) continue;
    out.dG[c].setZero();
    out.dg[c] = out.pair[c].G.transpose();
  }
}

std::vector<char> Discretization::contact_set(const State& state) const {
  std::vector<char> set(static_cast<std::size_t>(contact_count()), 0);
  ContactBlock block;
  for (int j = 0; j < contact_count(); ++j) {
    const int in_node = j % contact_pairs_per_node();
    const auto c = static_cast<std::size_t>(in_node % contact_candidates_);
    if (c == 0) contact_block(state, contact_node(j), in_node / contact_candidates_, false, block);
    const double kg = contact_stiffness_N_m_ * block.pair[c].gap_m;
    set[static_cast<std::size_t>(j)] =
        state.contact_lambda_N[static_cast<std::size_t>(j)] - kg > 0.0;
  }
  return set;
}

std::vector<rod::ContactSample> Discretization::contact_samples(const State& state,
                                                                int obstacle) const {
  std::vector<rod::ContactSample> samples;
  ContactBlock block;
  for (int k = 1; k < node_count(); ++k) {
    contact_block(state, k, obstacle, false, block);
    for (int c = 0; c < contact_candidates_; ++c) {
      const int j = (k - 1) * contact_pairs_per_node() + obstacle * contact_candidates_ + c;
      const ContactPair& pair = block.pair[static_cast<std::size_t>(c)];
      // A state without (these) multipliers: every pair open.
      const double lambda_N = static_cast<int>(state.contact_lambda_N.size()) == contact_count()
                                  ? state.contact_lambda_N[static_cast<std::size_t>(j)]
                                  : 0.0;
      rod::ContactSample sample;
      sample.s_m = state.s_m[static_cast<std::size_t>(k)];
      sample.point_W_m = state.p_W_m[static_cast<std::size_t>(k)] + pair.section.offset_W_m;
      sample.force_W_N =
          lambda_N > 0.0 ? Vector3d(lambda_N * pair.section.normal_W) : Vector3d::Zero();
      sample.gap_m = pair.gap_m;
      samples.push_back(sample);
    }
  }
  return samples;
}

rod::Wrench Discretization::base_reaction(const State& state, const LoadCase& loads,
                                          double lambda) const {
  // Node 0's rows of the first element: its internal force (world) and moment (material
  // frame of node 0: the virtual work M_W . dtheta_W = (R^T M_W) . dtheta_B). The clamp
  // balances them with the base node's weight share, which acts at the base point.
  ElementEvaluation ev;
  evaluate_element(state, 0, state.tensions_N, false, ev);
  rod::Wrench w;
  w.force_W_N = ev.residual.head<3>() - lambda * node_mass_kg_[0] * loads.loads.gravity_W_m_s2;
  w.moment_W_Nm = state.q_WB[0].toRotationMatrix() * ev.residual.segment<3>(3);
  return w;
}

Integration parse_integration(const std::string& text) {
  if (text == "reduced") return Integration::kReduced;
  if (text == "full") return Integration::kFull;
  throw InputError("integration", text, "must be `reduced` or `full`");
}

LinearSolver parse_linear_solver(const std::string& text) {
  if (text == "klu") return LinearSolver::kKlu;
  if (text == "umfpack") {
    load_linear_solver(LinearSolver::kUmfpack);
    return LinearSolver::kUmfpack;
  }
  if (text == "sparselu") return LinearSolver::kSparseLu;
  throw InputError("linear_solver", text, "must be `klu`, `umfpack` or `sparselu`");
}

}  // namespace tcasim::beam_fe
