#pragma once
/// Initial-value integration of dy/ds = f(s, y) behind one interface: fixed-step
/// classical RK4 ([Pawlowski2019] uses it) or SUNDIALS CVODE (adaptive Adams or BDF
/// with tolerance control). The SUNDIALS C API stays inside ode.cpp.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tcasim::ode {

/// dy/ds = f(s, y); writes into dyds (already sized). Exceptions thrown by f
/// propagate out of Integrator::integrate (also through CVODE).
using RhsFunction = std::function<void(double s, const Eigen::VectorXd& y, Eigen::VectorXd& dyds)>;
/// Called at each output point (see IntegratorOptions).
using Observer = std::function<void(double s, const Eigen::VectorXd& y)>;

enum class Method {
  kRk4,  ///< classical fourth-order Runge-Kutta, `steps` equal steps
  /// Butcher's seven-stage explicit Runge-Kutta method of order six ([Butcher2008], nodes
  /// c = 0, 1/3, 2/3, 1/3, 1/2, 1/2, 1), `steps` equal steps: 7/4 of RK4's cost per step,
  /// far fewer steps for a given error on smooth problems.
  kRk6,
  /// Cooper and Verner's eleven-stage explicit Runge-Kutta method of order eight
  /// ([CooperVerner1972], nodes 0, 1/2, 1/2, (7 -+ sqrt 21)/14, ..., 1), `steps` equal steps:
  /// 11/7 of RK6's cost per step, fewer steps again on smooth problems.
  kRk8,
  kCvode,  ///< SUNDIALS CVODE (scheme chosen by IntegratorOptions::cvode_scheme)
};

/// True for the fixed-step methods (kRk4, kRk6, kRk8), which use IntegratorOptions::steps.
constexpr bool is_fixed_step(Method m) {
  return m == Method::kRk4 || m == Method::kRk6 || m == Method::kRk8;
}
/// Order of a fixed-step method (4, 6 or 8); 0 for kCvode (variable order).
constexpr int order_of(Method m) {
  return m == Method::kRk4 ? 4 : m == Method::kRk6 ? 6 : m == Method::kRk8 ? 8 : 0;
}
/// Name used in messages and options: "rk4", "rk6", "rk8" or "cvode".
const char* to_string(Method m);

/// Butcher tableau of a fixed-step method: `stages` stages, a row-major stages x stages
/// (strictly lower triangular), weights b and nodes c: the tableau the integrator's steps
/// implement (for tests and documentation). Throws InputError for kCvode.
struct Tableau {
  int stages = 0;
  std::vector<double> a, b, c;
};
Tableau tableau(Method m);

/// CVODE's linear multistep family and nonlinear iteration.
enum class CvodeScheme {
  /// Adams-Moulton (orders 1..12) with fixed-point iteration: the default, most
  /// accurate per RHS evaluation on smooth non-stiff problems at tight tolerances.
  kAdamsFixedPoint,
  /// BDF (orders 1..5) with Newton iteration and a dense difference-quotient
  /// Jacobian: for stiff problems only.
  kBdfNewtonDense,
};

/// Options, validated by Integrator's constructor (InputError naming the field).
/// The most fixed steps along s the shooting method takes (statics and dynamics): RK4's error
/// falls like N^-4 and reaches round-off near the 2048 steps of the validation reference;
/// 100000 steps take about a second per solve, beyond that a run only burns time.
inline constexpr int kMaxFixedSteps = 100000;

struct IntegratorOptions {
  Method method = Method::kRk4;
  int steps = 100;                    ///< kRk4, kRk6, kRk8: number of equal steps (>= 1)
  double relative_tolerance = 1e-10;  ///< kCvode (> 0)
  double absolute_tolerance = 1e-14;  ///< kCvode (> 0), in the units of y
  long max_internal_steps = 100000;   ///< kCvode: max steps between two output points (>= 1)
  CvodeScheme cvode_scheme = CvodeScheme::kAdamsFixedPoint;  ///< kCvode
  /// Output points for the observer: s0 + k (s1 - s0)/output_intervals, k = 0..M (>= 0).
  /// The fixed-step methods observe at step nodes only, so output_intervals must divide
  /// `steps`; with output_intervals = 0 the observer sees every step node. kCvode with
  /// output_intervals = 0 observes s0 and s1 only (values between come from CVODE's
  /// interpolant, with the integration's accuracy).
  int output_intervals = 0;
};

struct IntegrationSummary {
  enum class Status {
    kSuccess,  ///< reached s1 with a finite y
    kFailed,   ///< the integrator stopped before s1 (message says why), or y became non-finite
  };
  Status status = Status::kSuccess;
  long rhs_evaluations = 0;  ///< all calls of f (CVODE: including difference-quotient Jacobians)
  long steps = 0;            ///< steps taken (kRk4: equal steps; kCvode: internal steps)
  /// s of the returned y: s1 on success; on failure the last s with a finite state.
  double s_final = 0.0;
  std::string message;  ///< empty on success
};

/// Reusable integrator for one state dimension (buffers and CVODE memory are kept
/// between calls, so repeated shooting integrations do not allocate for kRk4 and
/// re-initialize CVODE with CVodeReInit).
class Integrator {
 public:
  /// Throws InputError on bad options or dimension < 1, ExternalError if SUNDIALS
  /// setup fails.
  Integrator(int dimension, const IntegratorOptions& options);
  ~Integrator();
  Integrator(Integrator&&) noexcept;
  Integrator& operator=(Integrator&&) noexcept;
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// The options given at construction.
  const IntegratorOptions& options() const;
  /// Length of the state vector.
  int dimension() const;

  /// Integrates y from s0 to s1 > s0 in place. Throws InputError on bad arguments
  /// (s1 <= s0, non-finite s, y.size() != dimension, non-finite y) and ExternalError
  /// on a SUNDIALS error outside the integration proper; a failed integration is a
  /// status (then y holds the last finite state, at summary.s_final).
  IntegrationSummary integrate(const RhsFunction& f, double s0, double s1, Eigen::VectorXd& y,
                               const Observer& observer = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tcasim::ode
