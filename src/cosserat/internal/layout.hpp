#pragma once
/// The layout of a shooting problem: the few operations in which the 3-D problem (the state
/// and unknowns of cosserat/shooting.hpp) and its planar reduction (cosserat/internal/planar.hpp,
/// docs/conventions.md "Planar reduction") differ. The solver (ShootingSolver::Impl on the
/// layers RodProblem <- RodRhs <- TipConditions) is written once against this interface;
/// its two implementations are
///   layout_3d.cpp      the 3-D layout: the right-hand sides of rhs.cpp, the tip wrench and
///                      tip-constraint rows
///   planar_layout.cpp  the planar reduction: the right-hand sides and tip wrench of
///                      planar.cpp, when it applies, and its embedding into the 3-D layout
/// Its functions run once per IVP, residual or solve; the IVP's per-step right-hand sides
/// are the functions bind() installs (no virtual call inside the integration).
/// Internal to the shooting solver.
#include <Eigen/Core>
#include <memory>

#include "cosserat/shooting.hpp"

namespace tcasim::cosserat::internal {

struct RodRhs;
struct TipConditions;

/// Sizes and offsets of a layout's IVP state and unknowns.
struct LayoutDims {
  /// Leading unknowns: the strains at s = 0 (3-D: e_B, omega_B; planar: nu_x, nu_z - 1,
  /// omega_y); the TCA tensions follow.
  int strain_unknowns = 6;
  /// Index in y(0) of the (contiguous) strains that the leading unknowns set.
  int strain_offset = state_layout::kNu;
  /// Index of delta_0 in the state; the state dimension is delta_offset + actuators.
  int delta_offset = state_layout::kDelta;
};

class Layout {
 public:
  virtual ~Layout() = default;

  virtual LayoutDims dims() const = 0;
  /// Whether this layout is a reduction of the 3-D one (Summary::planar).
  virtual bool reduced() const = 0;
  /// Whether this layout solves `act` from `start` (3-D unknowns; a warm start when valid).
  virtual bool admits(const rod::Loads& act, const Solution& start) const = 0;

  /// Installs p.rhs and, with `sensitivities`, p.rhs_sens (RodRhs); they read the IVP
  /// parameters of p (and of this layout), which must outlive them.
  virtual void bind(RodRhs& p, bool sensitivities) = 0;
  /// Takes the IVP parameters RodRhs::set_parameters has just set in p (cT, f_ext_W).
  virtual void set_parameters(const RodRhs& p) = 0;
  /// y(0) (size p.dim) for this layout's unknowns x.
  virtual void initial_state(const RodRhs& p, const Eigen::VectorXd& x,
                             Eigen::VectorXd& y0) const = 0;
  /// The scaled residual's rows other than the TCA rows (tip wrench, tip constraint) at
  /// unknowns x with y(L) = yL, p's IVP parameters set for x (TipConditions::tip_residual).
  virtual void tip_rows(const TipConditions& p, const rod::Loads& act, double lambda,
                        const Eigen::VectorXd& x, const Eigen::VectorXd& yL,
                        Eigen::VectorXd& r) const = 0;
  /// The same rows of dr/dx (J is nx x nx) from y(L) = y and the augmented state Y(L)
  /// (TipConditions::tip_jacobian).
  virtual void tip_rows_jacobian(const TipConditions& p, const rod::Loads& act, double lambda,
                                 const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                                 const Eigen::VectorXd& Y, Eigen::MatrixXd& J) const = 0;

  /// 3-D unknowns to this layout's, in place (left alone unless x has the 3-D size).
  virtual void reduce_unknowns(Eigen::VectorXd& x) const = 0;
  /// This layout's unknowns to the 3-D ones, in place.
  virtual void embed_unknowns(Eigen::VectorXd& x) const = 0;
  /// This layout's IVP state y as the 3-D one y3 (cosserat/shooting.hpp); y3 is resized only
  /// when its size differs (sampling reuses it), and must not be y.
  virtual void embed_state(const Eigen::VectorXd& y, Eigen::VectorXd& y3) const = 0;
};

/// The 3-D layout of cosserat/shooting.hpp (layout_3d.cpp).
std::unique_ptr<Layout> make_3d_layout();

/// The planar reduction (planar_layout.cpp) when the model and options admit it: straight
/// strings on the body x axis, reference curvature about y, a uniform body, no tip
/// constraint, a fixed-step flat integration with sensitivity Jacobians (o: the validated
/// options of the 3-D solver), and at most planar::kMaxActuators actuators and
/// planar::kMaxDirections unknowns; else nullptr. Its admits() checks the loads per solve.
std::unique_ptr<Layout> make_planar_layout(const rod::RodModel& m, const Options& o);

}  // namespace tcasim::cosserat::internal
