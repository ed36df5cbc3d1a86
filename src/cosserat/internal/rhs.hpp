#pragma once
/// Right-hand side of the shooting IVP and of its forward sensitivities (the variational
/// equations), docs/conventions.md "Body-frame ODEs solved by the shooting solver", with the
/// IVP parameters (string tensions c_i T_i, distributed load) of the current evaluation.
/// The layout (cosserat/internal/layout.hpp) installs the right-hand sides the IVP integrates:
/// these (3-D) or the planar reduction's (cosserat/internal/planar.hpp). Internal to the shooting
/// solver.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "common/ode.hpp"
#include "cosserat/internal/integration_level.hpp"
#include "cosserat/internal/layout.hpp"
#include "cosserat/internal/problem.hpp"
#include "cosserat/shooting.hpp"
#include "tca/tca.hpp"

namespace tcasim::cosserat::internal {

struct RodRhs : RodProblem {
  /// layout: the state layout and its right-hand sides (cosserat/internal/layout.hpp);
  /// sensitivities: also build the variational right-hand side `rhs_sens` (not with more
  /// than kMaxSensitivityUnknowns unknowns).
  RodRhs(const rod::RodModel& m, std::unique_ptr<Layout> layout, bool sensitivities);
  RodRhs(const RodRhs&) = delete;  // the right-hand sides capture `this`
  RodRhs& operator=(const RodRhs&) = delete;

  // docs/conventions.md "Body-frame ODEs solved by the shooting solver".
  void eval_rhs(double s, const Eigen::VectorXd& yy, Eigen::VectorXd& dy) const;
  /// RHS of the state and of its forward sensitivities Y_j = dy/dx_j (the variational
  /// equations Y_j' = (df/dy) Y_j + df/dx_j, x_j = T_k entering through c_k T_k). Layout:
  /// Y = (y, Y_0, ..., Y_{nx-1}), each block of length `dim`. The directional derivative
  /// of the linear system M z = b is dz = M^-1 (db - dM z), with the same LU as z.
  void eval_rhs_sens(double s, const Eigen::VectorXd& Ya, Eigen::VectorXd& dY) const;
  /// Sets cT and f_ext for load fraction lambda and unknowns x; fills scaled segments.
  void set_parameters(const rod::Loads& act, double lambda, const Eigen::VectorXd& x);
  /// y(0) for unknowns x (the layout's state and unknowns).
  void initial_state(const Eigen::VectorXd& x, Eigen::VectorXd& y0) const {
    layout->initial_state(*this, x, y0);
  }

  /// Stiffnesses (and reciprocals), omega* and weight factor at s: the constant members for
  /// a uniform body, else the model's values on the side of s inside the current piece.
  /// With their s-derivatives dKn, dKw, dws (varying bodies only; zero otherwise).
  struct Local {
    Vec3 Kn, Kw, Kn_inv, Kw_inv, ws;
    double wf = 1.0;
    Vec3 dKn = Vec3::Zero(), dKw = Vec3::Zero(), dws = Vec3::Zero();
  };
  /// local(s) of a varying body reads the memo below (filled by model_local on a miss).
  /// The reference stays valid until the next call of local().
  const Local& local(double s) const {
    if (uniform) return uniform_local;
    const rod::Side side = s < piece_mid ? rod::Side::kRight : rod::Side::kLeft;
    const Local* k = memo.find(s, side);
    if (k == nullptr) k = &memo.insert(s, side, model_local(s, side));
    if (omega_star_fraction == 1.0) return *k;
    // The homotopy in omega*'s variation (RodProblem::set_omega_star_fraction), as
    // RodProblem::properties applies it.
    homotopy_local = *k;
    homotopy_local.ws = homotopy_omega_star(k->ws);
    homotopy_local.dws *= omega_star_fraction;
    return homotopy_local;
  }
  /// The model's Local at s on `side` (omega* and its slope at mu = 1): the profile
  /// evaluations local() memoizes.
  Local model_local(double s, rod::Side side) const;

  /// The Locals of a varying body at the (s, side) the integrations visit. Each level
  /// integrates on a fixed grid (fixed-step methods), so every IVP after the first finds its
  /// stages here instead of evaluating the profiles again. An entry is the model's exact
  /// value at its s (no interpolation): a hit returns the same bits as an evaluation.
  /// Open addressing on the bits of s, the table doubling at load 1/2; beyond kMaxEntries
  /// distinct points (CVODE's adaptive s, very fine grids) further points are evaluated
  /// without being stored.
  class LocalMemo {
   public:
    /// The entry of (s, side), or nullptr.
    const Local* find(double s, rod::Side side) const;
    /// Stores k as the entry of (s, side) (absent before) and returns the entry; once the
    /// memo is full, returns a copy that the next insert() overwrites.
    const Local& insert(double s, rod::Side side, const Local& k);
    /// The number of (s, side) held.
    std::size_t size() const { return entries_.size(); }

   private:
    static constexpr std::size_t kMaxEntries = 4096;
    std::size_t slot_of(double s, rod::Side side) const;
    struct Entry {
      double s;
      rod::Side side;
      Local k;
    };
    std::vector<int> slot_;  // index into entries_, -1 if free; size a power of two
    int slot_bits_ = 0;
    std::vector<Entry> entries_;
    Local overflow_;  // the value insert() returns once the memo is full
  };
  mutable LocalMemo memo;
  Local uniform_local;           // a uniform body's Local (the constant members)
  mutable Local homotopy_local;  // local() during the homotopy in omega* (mu != 1)

  /// A body varying along s: the pieces of the IVP (nullptr for a uniform body).
  const internal::PieceHooks* piece_hooks() const { return knots.empty() ? nullptr : &pieces; }
  /// The strain jump at knot k (docs/conventions.md "Bodies that vary along s"): the total
  /// wrench across the section, rod plus strings (body frame),
  ///   W(z, s) = ( K_nu(s) e + sum c_i T_i qh_i,  K_omega(s) (omega - omega*(s)) + sum c_i T_i
  ///   r_i x qh_i ),
  /// is continuous, so z+ = (e, omega) on the right solves W(z+, s+) = W(z-, s-) (Newton with
  /// the exact derivative, the strain system matrix M; direct without loaded strings). With
  /// `directions` > 0, Y holds the sensitivity blocks too: dz+ = M+^-1 (M- dz- + sum_i dcT_i
  /// (u_i(z-) - u_i(z+))), u_i = (qh_i, r_i x qh_i). False if the Newton iteration fails.
  bool strain_jump(std::size_t k, Eigen::VectorXd& Y, int directions) const;
  /// A point wrench on the body at s (a contact force, docs/conventions.md "Contact in the
  /// shooting method"): force f_B and moment m_B (about p, body frame) applied to the rod at
  /// s make the total section wrench (rod plus the strings crossing, RodRhs::strain_jump's W)
  /// jump by -(f_B, m_B); the strains in y (state only) become the z+ solving
  /// W(z+) = W(z-) - (f_B, m_B), with the properties of the piece being integrated (s on
  /// the side of its midpoint). Direct without loaded strings, else Newton. False if that
  /// fails.
  bool point_wrench_jump(double s, const Vec3& f_B, const Vec3& m_B, Eigen::VectorXd& y) const;

  // Current IVP parameters (set_parameters, before each integration).
  std::vector<double> cT;  // count * tension per actuator
  Vec3 f_ext_W = Vec3::Zero();
  std::vector<std::vector<tca::Segment>> scaled_segments;  // TCA segments at the load fraction
  std::unique_ptr<Layout> layout;  // 3-D or the planar reduction (cosserat/internal/layout.hpp)
  ode::RhsFunction rhs;            // y' = f(s, y), installed by the layout
  ode::RhsFunction rhs_sens;       // (y, Y_j)' (sensitivities only), installed by the layout

  /// Per-actuator quantities shared by the state and sensitivity parts of the RHS.
  struct ActuatorCache {
    Vec3 r, dr, qh, v, Pv, gb, Pw;
    double q_norm = 1.0;
  };
  mutable std::vector<ActuatorCache> cache;
  internal::PieceHooks pieces;     // non-uniform bodies: the knots and the jump functions
  mutable double piece_mid = 0.0;  // midpoint of the piece being integrated
  mutable std::size_t piece = 0;   // index of the piece being integrated (string_runs)
  mutable Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxSensitivityUnknowns> rhs_ws;  // 6 x nx
};

}  // namespace tcasim::cosserat::internal
