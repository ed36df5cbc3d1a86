// Mesh, degrees of freedom and global assembly of the beam FE problem.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "common/so3.hpp"

namespace tcasim::beam_fe {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

/// Current tension of one string of a TCA drive and dF/d(elongation).
struct TcaTension {
  double tension_N, dF_ddelta_N_m;
};

TcaTension tca_tension(const rod::Actuator& act, double elongation_m, double start_K, double lambda) {
  const rod::Drive& drive = act.drive;
  // Temperatures ramp from the material's reference temperature with the load factor.
  std::vector<tca::Segment> segments = drive.segments;
  for (tca::Segment& seg : segments) seg.temperature_K = start_K + lambda * (seg.temperature_K - start_K);
  if (segments.size() == 1) {
    const tca::TensionState t = drive.tca->tension(elongation_m, segments[0].temperature_K);
    return {t.tension_N, t.dF_ddelta_N_m};
  }
  const tca::SeriesTensionState t = tca::series_tension(*drive.tca, elongation_m, segments);
  return {t.tension_N, t.dF_ddelta_N_m};
}

}  // namespace

Discretization::Discretization(const rod::RodModel& model, const Options& options)
    : model_(&model), elements_(options.elements), order_(options.order) {
  require(options.elements >= 1, "elements", options.elements, "must be >= 1");
  require(options.order == 1 || options.order == 2, "order", options.order, "must be 1 or 2");
  require(options.tolerance_abs >= 0.0, "tolerance_abs", options.tolerance_abs, "must be >= 0");
  require(options.tolerance_rel >= 0.0, "tolerance_rel", options.tolerance_rel, "must be >= 0");
  require(options.max_iterations >= 1, "max_iterations", options.max_iterations, "must be >= 1");
  require(options.initial_load_step > 0.0 && options.initial_load_step <= 1.0, "initial_load_step",
          options.initial_load_step, "must be in (0, 1]");
  require(model.length_m > 0.0, "body.length_m", model.length_m, "must be > 0");
  h_m_ = model.length_m / elements_;

  // Gauss-Legendre points on [-1, 1].
  const int points = order_ + (options.integration == Integration::kFull ? 1 : 0);
  if (points == 1) {
    quad_ = {{0.0}, {2.0}};
  } else if (points == 2) {
    const double x = 1.0 / std::sqrt(3.0);
    quad_ = {{-x, x}, {1.0, 1.0}};
  } else {
    const double x = std::sqrt(0.6);
    quad_ = {{-x, 0.0, x}, {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}};
  }

  tca_unknown_.assign(model.actuators.size(), -1);
  start_temperature_K_.assign(model.actuators.size(), 0.0);
  for (std::size_t i = 0; i < model.actuators.size(); ++i) {
    const rod::Actuator& act = model.actuators[i];
    if (act.drive.type != rod::Drive::Type::kTca) continue;
    if (!act.drive.tca || act.drive.segments.empty()) {
      throw InputError(fmt::format("actuators[{}].drive", i), act.drive.tca_id,
                       "a TCA drive needs a resolved TCA and at least one segment");
    }
    tca_unknown_[i] = static_cast<int>(tca_actuators_.size());
    tca_actuators_.push_back(static_cast<int>(i));
    const tca::Material& mat = act.drive.tca->material();
    start_temperature_K_[i] =
        std::clamp(mat.reference_temperature_K, mat.min_temperature_K, mat.max_temperature_K);
  }

  // Consistent nodal dead loads: gravity int N_a psi A g ds (exact with the element rule:
  // degree order <= 2 p - 1) and the tip force.
  const int nodes = node_count();
  nodal_dead_load_ = VectorXd::Zero(6 * (nodes - 1));
  const Vector3d f_W = model.weight_per_length_W_N_m();
  for (int e = 0; e < elements_; ++e) {
    for (std::size_t g = 0; g < quad_.xi.size(); ++g) {
      const double xi = quad_.xi[g];
      const double wj = quad_.weight[g] * 0.5 * h_m_;
      double N[3];
      if (order_ == 1) {
        N[0] = 0.5 * (1.0 - xi);
        N[1] = 0.5 * (1.0 + xi);
      } else {
        N[0] = 0.5 * xi * (xi - 1.0);
        N[1] = 1.0 - xi * xi;
        N[2] = 0.5 * xi * (xi + 1.0);
      }
      for (int a = 0; a <= order_; ++a) {
        const int node = e * order_ + a;
        if (node == 0) continue;
        nodal_dead_load_.segment<3>(6 * (node - 1)) += wj * N[a] * f_W;
      }
    }
  }
  nodal_dead_load_.segment<3>(6 * (nodes - 2)) += model.tip_force_W_N;
}

State Discretization::reference_state() const {
  const rod::RodModel& model = *model_;
  State st;
  const int nodes = node_count();
  const Eigen::Quaterniond q0(model.R_WB0);
  for (int k = 0; k < nodes; ++k) {
    const double s = model.length_m * k / (nodes - 1);
    const Vector3d phi = s * model.reference_curvature_B_1_m;
    st.s_m.push_back(s);
    // Exact arc of constant curvature: R = R0 exp(s omega*), p = p0 + R0 s Jl(s omega*) e3.
    st.p_W_m.push_back(model.base_position_W_m +
                       model.R_WB0 * (s * so3::left_jacobian(phi) * Vector3d::UnitZ()));
    st.q_WB.push_back((q0 * so3::exp_quaternion(phi)).normalized());
  }
  st.tensions_N.assign(model.actuators.size(), 0.0);
  st.load_factor = 0.0;
  return st;
}

void Discretization::apply_prescribed_tensions(State& state, double lambda) const {
  for (std::size_t i = 0; i < model_->actuators.size(); ++i) {
    const rod::Drive& d = model_->actuators[i].drive;
    if (d.type == rod::Drive::Type::kTension) state.tensions_N[i] = lambda * d.tension_N;
  }
}

void Discretization::retract(State& state, const VectorXd& dx) const {
  const int nodes = node_count();
  for (int k = 1; k < nodes; ++k) {
    state.p_W_m[k] += dx.segment<3>(6 * (k - 1));
    state.q_WB[k] = (state.q_WB[k] * so3::exp_quaternion(dx.segment<3>(6 * (k - 1) + 3))).normalized();
  }
  for (std::size_t j = 0; j < tca_actuators_.size(); ++j) {
    state.tensions_N[tca_actuators_[j]] += dx[6 * (nodes - 1) + static_cast<int>(j)];
  }
}

std::vector<double> Discretization::string_lengths(const State& state) const {
  std::vector<double> l(model_->actuators.size(), 0.0);
  ElementEvaluation ev;
  for (int e = 0; e < elements_; ++e) {
    evaluate_element(state, e, state.tensions_N, false, ev);
    for (std::size_t i = 0; i < l.size(); ++i) l[i] += ev.lengths_m[i];
  }
  return l;
}

double Discretization::residual_scale(const State& state, double lambda) const {
  double scale = lambda * nodal_dead_load_.cwiseAbs().maxCoeff();
  scale = std::max(scale, lambda * model_->tip_moment_W_Nm.cwiseAbs().maxCoeff());
  for (std::size_t i = 0; i < model_->actuators.size(); ++i) {
    scale = std::max(scale, model_->actuators[i].count * std::abs(state.tensions_N[i]));
  }
  return scale;
}

Discretization::Floor Discretization::round_off_floor() const {
  // Strains are differences of nodal values divided by the node spacing L/(nodes - 1), so
  // they carry round-off ~eps (nodes - 1); times the stiffness and a factor 10 for the
  // sums, that is the level below which the assembled residual cannot be resolved
  // (measured: force rows ~0.06, moment rows ~0.02 of these bounds). Moment rows also pick
  // up the force round-off times the node spacing h.
  constexpr double kRoundOffTerms = 10.0;
  const double eps_n = kRoundOffTerms * std::numeric_limits<double>::epsilon() * node_count();
  const double force = eps_n * model_->shear_extension_stiffness().maxCoeff();
  const double moment = eps_n * model_->bending_torsion_stiffness().maxCoeff() / model_->length_m +
                        force * model_->length_m / (node_count() - 1);
  return {force, moment};
}

bool Discretization::within_tolerance(const VectorXd& r, const State& state, double lambda,
                                      const Options& options) const {
  const double base = options.tolerance_abs + options.tolerance_rel * residual_scale(state, lambda);
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
int slot(const Eigen::SparseMatrix<double>& K, int i, int j) {
  const int* inner = K.innerIndexPtr();
  const int* begin = inner + K.outerIndexPtr()[j];
  const int* end = inner + K.outerIndexPtr()[j + 1];
  const int* it = std::lower_bound(begin, end, i);
  assert(it != end && *it == i);
  return static_cast<int>(it - inner);
}
}  // namespace

void Discretization::assemble_pattern(Eigen::SparseMatrix<double>& K) const {
  const int n = dof_count();
  const int free_dofs = 6 * (node_count() - 1);
  std::vector<Eigen::Triplet<double>> trip;
  const int nd = 6 * (order_ + 1);
  for (int e = 0; e < elements_; ++e) {
    for (int i = 0; i < nd; ++i) {
      const int gi = 6 * (e * order_) + i - 6;
      if (gi < 0) continue;
      for (int j = 0; j < nd; ++j) {
        const int gj = 6 * (e * order_) + j - 6;
        if (gj >= 0) trip.emplace_back(gi, gj, 0.0);
      }
    }
  }
  for (int t = free_dofs; t < n; ++t) {
    for (int k = 0; k < n; ++k) {
      trip.emplace_back(t, k, 0.0);
      if (k < free_dofs) trip.emplace_back(k, t, 0.0);
    }
  }
  K.resize(n, n);
  K.setFromTriplets(trip.begin(), trip.end());
  K.makeCompressed();
  // Where each element entry and each bordered entry lives in K's values.
  element_slots_.assign(static_cast<std::size_t>(elements_) * nd * nd, -1);
  for (int e = 0; e < elements_; ++e) {
    for (int i = 0; i < nd; ++i) {
      const int gi = 6 * (e * order_) + i - 6;
      for (int j = 0; j < nd; ++j) {
        const int gj = 6 * (e * order_) + j - 6;
        if (gi >= 0 && gj >= 0) element_slots_[(static_cast<std::size_t>(e) * nd + i) * nd + j] = slot(K, gi, gj);
      }
    }
  }
  tca_slots_.clear();
  for (int t = free_dofs; t < n; ++t) {
    for (int k = 0; k < free_dofs; ++k) tca_slots_.push_back(slot(K, t, k));
    for (int k = 0; k < free_dofs; ++k) tca_slots_.push_back(slot(K, k, t));
    tca_slots_.push_back(slot(K, t, t));
  }
}

VectorXd Discretization::residual(const State& state, double lambda,
                                  Eigen::SparseMatrix<double>* tangent) const {
  const rod::RodModel& model = *model_;
  const int n = dof_count();
  const int nodes = node_count();
  const int free_dofs = 6 * (nodes - 1);
  const int nd = 6 * (order_ + 1);
  VectorXd r = VectorXd::Zero(n);
  double* values = nullptr;
  if (tangent) {
    if (tangent->rows() != n || tangent->nonZeros() == 0 || element_slots_.empty()) assemble_pattern(*tangent);
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
  // External loads: dead nodal forces, and the world-frame tip moment M_e whose virtual
  // work M_e . dtheta_W = (R^T M_e) . dtheta_B gives m(L) = M_e.
  r.head(free_dofs) -= lambda * nodal_dead_load_;
  const Matrix3d R_tip = state.q_WB.back().toRotationMatrix();
  const Vector3d M_B = lambda * R_tip.transpose() * model.tip_moment_W_Nm;
  const int tip_rot = free_dofs - 3;
  r.segment<3>(tip_rot) -= M_B;
  if (tangent) {
    // d/deta of -exp(-eta) R^T M = -hat(R^T M).
    const Matrix3d Km = -so3::hat(M_B);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) tangent->coeffRef(tip_rot + i, tip_rot + j) += Km(i, j);
  }
  // TCA rows: T_i - F_tca(l_i - rest_i); columns: c_i dl_i/dq.
  const std::size_t stride = 2 * static_cast<std::size_t>(free_dofs) + 1;
  for (std::size_t j = 0; j < tca_actuators_.size(); ++j) {
    const int a = tca_actuators_[j];
    const rod::Actuator& act = model.actuators[a];
    const int row = free_dofs + static_cast<int>(j);
    const TcaTension f =
        tca_tension(act, lengths[a] - act.rest_length_m, start_temperature_K_[a], lambda);
    r[row] = state.tensions_N[a] - f.tension_N;
    if (!tangent) continue;
    const int* slots = &tca_slots_[j * stride];
    for (int k = 0; k < free_dofs; ++k) {
      values[slots[k]] += -f.dF_ddelta_N_m * dl[a][k];
      values[slots[free_dofs + k]] += act.count * dl[a][k];
    }
    values[slots[2 * free_dofs]] += 1.0;
  }
  return r;
}

Integration parse_integration(const std::string& text) {
  if (text == "reduced") return Integration::kReduced;
  if (text == "full") return Integration::kFull;
  throw InputError("integration", text, "must be `reduced` or `full`");
}

LinearSolver parse_linear_solver(const std::string& text) {
  if (text == "klu") return LinearSolver::kKlu;
  if (text == "umfpack") return LinearSolver::kUmfpack;
  if (text == "sparselu") return LinearSolver::kSparseLu;
  throw InputError("linear_solver", text, "must be `klu`, `umfpack` or `sparselu`");
}

}  // namespace tcasim::beam_fe
