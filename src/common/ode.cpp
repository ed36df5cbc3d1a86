#include "common/ode.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>
#include <cstdlib>
#include <exception>
#include <memory>
#include <type_traits>
#include <utility>

#include "common/error.hpp"

// CVODE method choice. The rod IVPs of the shooting solver are smooth and non-stiff
// and are solved at tight tolerances (rtol ~ 1e-10). Adams-Moulton reaches order 12
// there (BDF stops at 5), so it takes far fewer steps per digit, and a fixed-point
// corrector needs no Jacobian (a dense difference-quotient Jacobian costs n extra RHS
// calls per update). BDF is also not A-stable beyond order 2 and damps the
// oscillatory modes of the rod equations. BDF + dense Newton stays available as
// CvodeScheme::kBdfNewtonDense for stiff problems.

namespace tcasim::ode {
namespace {

// ---- RAII owners of the SUNDIALS objects ----------------------------------------
struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix m) const { SUNMatDestroy(m); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver ls) const { SUNLinSolFree(ls); }
};
struct NonlinearSolverDeleter {
  void operator()(SUNNonlinearSolver nls) const { SUNNonlinSolFree(nls); }
};
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};
using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using NonlinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinearSolverDeleter>;
using CvodeMemPtr = std::unique_ptr<void, CvodeDeleter>;

/// CVODE's name of a return flag (the string is malloc'ed by SUNDIALS).
std::string cvode_flag_name(int flag) {
  char* name = CVodeGetReturnFlagName(flag);
  std::string out = name != nullptr ? name : fmt::format("flag {}", flag);
  std::free(name);
  return out;
}

std::string cvode_ls_flag_name(int flag) {
  char* name = CVodeGetLinReturnFlagName(flag);
  std::string out = name != nullptr ? name : fmt::format("flag {}", flag);
  std::free(name);
  return out;
}

/// Converts a failed CVODE setup call into ExternalError.
void check_cvode(int flag, const char* call) {
  if (flag < 0)
    throw ExternalError(fmt::format("SUNDIALS {} failed: {}", call, cvode_flag_name(flag)));
}

template <class T>
T check_created(T object, const char* call) {
  if (object == nullptr) throw ExternalError(fmt::format("SUNDIALS {} returned NULL", call));
  return object;
}

void validate(int dimension, const IntegratorOptions& o) {
  require(dimension >= 1, "dimension", dimension, "must be >= 1");
  require(o.output_intervals >= 0, "output_intervals", o.output_intervals, "must be >= 0");
  if (is_fixed_step(o.method)) {
    require(o.steps >= 1, "steps", o.steps, "must be >= 1");
    if (o.output_intervals != 0 && o.steps % o.output_intervals != 0)
      throw InputError("output_intervals", std::to_string(o.output_intervals),
                       fmt::format("must divide steps = {} ({} observes at step nodes)", o.steps,
                                   to_string(o.method)));
  } else {
    require(o.relative_tolerance > 0.0, "relative_tolerance", o.relative_tolerance, "must be > 0");
    require(o.absolute_tolerance > 0.0, "absolute_tolerance", o.absolute_tolerance, "must be > 0");
    require(o.max_internal_steps >= 1, "max_internal_steps",
            static_cast<double>(o.max_internal_steps), "must be >= 1");
  }
}

/// The k-th of M output points in [s0, s1]; the last one is exactly s1.
double output_point(double s0, double s1, int k, int M) {
  return k == M ? s1 : s0 + (s1 - s0) * (static_cast<double>(k) / M);
}

}  // namespace

const char* to_string(Method m) {
  switch (m) {
    case Method::kRk4:
      return "rk4";
    case Method::kRk6:
      return "rk6";
    case Method::kRk8:
      return "rk8";
    case Method::kCvode:
      return "cvode";
  }
  return "unknown";
}

struct Integrator::Impl {
  Impl(int n, const IntegratorOptions& o)
      : options(o), dimension(n), k1(n), k2(n), k3(n), k4(n), y_stage(n), y_next(n) {
    if (options.method == Method::kRk6 || options.method == Method::kRk8) {
      k5.resize(n);
      k6.resize(n);
      k7.resize(n);
    }
    if (options.method == Method::kRk8) {
      k8.resize(n);
      k9.resize(n);
      k10.resize(n);
      k11.resize(n);
    }
    if (options.method == Method::kCvode) setup_cvode();
  }

  IntegratorOptions options;
  int dimension;
  // Fixed-step work vectors (also the CVODE RHS copy buffers y_stage -> k1); k5..k7 for kRk6
  // and kRk8, k8..k11 for kRk8.
  Eigen::VectorXd k1, k2, k3, k4, k5, k6, k7, k8, k9, k10, k11, y_stage, y_next;

  // CVODE objects, declared so that they are destroyed in reverse dependency order
  // (CVODE memory first, the context last).
  ContextPtr context;
  VectorPtr y_nv;
  MatrixPtr matrix;
  LinearSolverPtr linear_solver;
  NonlinearSolverPtr nonlinear_solver;
  CvodeMemPtr cvode;

  // State of the current integrate() call, read by the CVODE callbacks.
  const RhsFunction* rhs = nullptr;
  long rhs_count = 0;
  std::exception_ptr rhs_exception;
  std::string last_cvode_message;

  void setup_cvode();
  static int cvode_rhs(realtype s, N_Vector y, N_Vector ydot, void* user_data);
  static void cvode_error_handler(int code, const char* module, const char* function, char* msg,
                                  void* user_data);

  /// kRk4, kRk6 and kRk8: equal steps, observer at step nodes.
  IntegrationSummary integrate_fixed(const RhsFunction& f, double s0, double s1, Eigen::VectorXd& y,
                                     const Observer& observer);
  /// One step of the fixed-step method from (s, y) to s_next = s + h; result in y_next.
  void rk4_step(const RhsFunction& f, double s, double h, double s_next, const Eigen::VectorXd& y);
  void rk6_step(const RhsFunction& f, double s, double h, double s_next, const Eigen::VectorXd& y);
  void rk8_step(const RhsFunction& f, double s, double h, double s_next, const Eigen::VectorXd& y);
  IntegrationSummary integrate_cvode(const RhsFunction& f, double s0, double s1, Eigen::VectorXd& y,
                                     const Observer& observer);
};

void Integrator::Impl::setup_cvode() {
  SUNContext ctx = nullptr;
  const int ctx_flag = SUNContext_Create(nullptr, &ctx);
  if (ctx_flag != 0 || ctx == nullptr)
    throw ExternalError(fmt::format("SUNDIALS SUNContext_Create failed with flag {}", ctx_flag));
  context.reset(ctx);
  y_nv.reset(check_created(N_VNew_Serial(dimension, ctx), "N_VNew_Serial"));
  N_VConst(0.0, y_nv.get());

  const bool adams = options.cvode_scheme == CvodeScheme::kAdamsFixedPoint;
  cvode.reset(check_created(CVodeCreate(adams ? CV_ADAMS : CV_BDF, ctx), "CVodeCreate"));
  void* mem = cvode.get();
  // Placeholder initial condition; every integrate() calls CVodeReInit.
  check_cvode(CVodeInit(mem, &Impl::cvode_rhs, 0.0, y_nv.get()), "CVodeInit");
  check_cvode(CVodeSetErrHandlerFn(mem, &Impl::cvode_error_handler, this), "CVodeSetErrHandlerFn");
  check_cvode(CVodeSetUserData(mem, this), "CVodeSetUserData");
  check_cvode(CVodeSStolerances(mem, options.relative_tolerance, options.absolute_tolerance),
              "CVodeSStolerances");
  check_cvode(CVodeSetMaxNumSteps(mem, options.max_internal_steps), "CVodeSetMaxNumSteps");
  if (adams) {
    // Plain fixed-point iteration (no Anderson acceleration).
    nonlinear_solver.reset(
        check_created(SUNNonlinSol_FixedPoint(y_nv.get(), 0, ctx), "SUNNonlinSol_FixedPoint"));
    check_cvode(CVodeSetNonlinearSolver(mem, nonlinear_solver.get()), "CVodeSetNonlinearSolver");
  } else {
    matrix.reset(check_created(SUNDenseMatrix(dimension, dimension, ctx), "SUNDenseMatrix"));
    linear_solver.reset(
        check_created(SUNLinSol_Dense(y_nv.get(), matrix.get(), ctx), "SUNLinSol_Dense"));
    const int flag = CVodeSetLinearSolver(mem, linear_solver.get(), matrix.get());
    if (flag != CVLS_SUCCESS)
      throw ExternalError(
          fmt::format("SUNDIALS CVodeSetLinearSolver failed: {}", cvode_ls_flag_name(flag)));
  }
}

int Integrator::Impl::cvode_rhs(realtype s, N_Vector y, N_Vector ydot, void* user_data) {
  auto* self = static_cast<Impl*>(user_data);
  // No exception may cross the C library: keep it and stop CVODE (unrecoverable).
  try {
    const Eigen::Map<const Eigen::VectorXd> y_in(N_VGetArrayPointer(y), self->dimension);
    self->y_stage = y_in;
    ++self->rhs_count;
    (*self->rhs)(s, self->y_stage, self->k1);
    // A non-finite slope is a recoverable failure: CVODE retries with a smaller step.
    if (!self->k1.allFinite()) return 1;
    Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(ydot), self->dimension) = self->k1;
    return 0;
  } catch (...) {
    self->rhs_exception = std::current_exception();
    return -1;
  }
}

void Integrator::Impl::cvode_error_handler(int code, const char* module, const char* function,
                                           char* msg, void* user_data) {
  // Keep the text for the summary instead of printing it to stderr.
  auto* self = static_cast<Impl*>(user_data);
  self->last_cvode_message = fmt::format(
      "{} {} ({}): {}", module != nullptr ? module : "", function != nullptr ? function : "",
      code == CV_WARNING ? "warning" : cvode_flag_name(code), msg != nullptr ? msg : "");
}

void Integrator::Impl::rk4_step(const RhsFunction& f, double s, double h, double s_next,
                                const Eigen::VectorXd& y) {
  // Classical RK4: y+ = y + h/6 (k1 + 2 k2 + 2 k3 + k4).
  f(s, y, k1);
  y_stage = y + (0.5 * h) * k1;
  f(s + 0.5 * h, y_stage, k2);
  y_stage = y + (0.5 * h) * k2;
  f(s + 0.5 * h, y_stage, k3);
  y_stage = y + h * k3;
  f(s_next, y_stage, k4);
  y_next = y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

void Integrator::Impl::rk6_step(const RhsFunction& f, double s, double h, double s_next,
                                const Eigen::VectorXd& y) {
  // Butcher's seven-stage sixth-order tableau ([Butcher2008]):
  //   c   | A
  //   1/3 | 1/3
  //   2/3 | 0     2/3
  //   1/3 | 1/12  1/3   -1/12
  //   1/2 | -1/16 9/8   -3/16  -3/8
  //   1/2 | 0     9/8   -3/8   -3/4  1/2
  //   1   | 9/44  -9/11 63/44  18/11 0    -16/11
  //   b   = 11/120, 0, 27/40, 27/40, -4/15, -4/15, 11/120
  f(s, y, k1);
  y_stage = y + (h / 3.0) * k1;
  f(s + h / 3.0, y_stage, k2);
  y_stage = y + (2.0 * h / 3.0) * k2;
  f(s + 2.0 * h / 3.0, y_stage, k3);
  y_stage = y + (h / 12.0) * (k1 + 4.0 * k2 - k3);
  f(s + h / 3.0, y_stage, k4);
  y_stage = y + (h / 16.0) * (-k1 + 18.0 * k2 - 3.0 * k3 - 6.0 * k4);
  f(s + 0.5 * h, y_stage, k5);
  y_stage = y + (h / 8.0) * (9.0 * k2 - 3.0 * k3 - 6.0 * k4 + 4.0 * k5);
  f(s + 0.5 * h, y_stage, k6);
  y_stage = y + (h / 44.0) * (9.0 * k1 - 36.0 * k2 + 63.0 * k3 + 72.0 * k4 - 64.0 * k6);
  f(s_next, y_stage, k7);
  y_next = y + (h / 120.0) * (11.0 * (k1 + k7) + 81.0 * (k3 + k4) - 32.0 * (k5 + k6));
}

namespace {
/// [CooperVerner1972] tableau (exact values in Q(sqrt 21); all 200 order conditions up to
/// order eight hold exactly, none of order nine in general). Row i lists a_i1 .. a_i,i-1.
constexpr double kR21 = 4.58257569495584000658804719372800848898;  // sqrt(21)
// The interior nodes of five-point Lobatto quadrature (c_4 and c_7).
constexpr double kC4 = (7.0 - kR21) / 14.0, kC7 = (7.0 + kR21) / 14.0;
constexpr double a41 = 1.0 / 7.0, a42 = (-7.0 + 3.0 * kR21) / 98.0,
                 a43 = (21.0 - 5.0 * kR21) / 49.0;
constexpr double a51 = (11.0 - kR21) / 84.0, a53 = (18.0 - 4.0 * kR21) / 63.0,
                 a54 = (21.0 + kR21) / 252.0;
constexpr double a61 = (5.0 - kR21) / 48.0, a63 = (9.0 - kR21) / 36.0,
                 a64 = (-231.0 - 14.0 * kR21) / 360.0, a65 = (63.0 + 7.0 * kR21) / 80.0;
constexpr double a71 = (10.0 + kR21) / 42.0, a73 = (-432.0 - 92.0 * kR21) / 315.0,
                 a74 = (633.0 + 145.0 * kR21) / 90.0, a75 = (-504.0 - 115.0 * kR21) / 70.0,
                 a76 = (63.0 + 13.0 * kR21) / 35.0;
constexpr double a81 = 1.0 / 14.0, a85 = (14.0 + 3.0 * kR21) / 126.0,
                 a86 = (13.0 + 3.0 * kR21) / 63.0, a87 = 1.0 / 9.0;
constexpr double a91 = 1.0 / 32.0, a95 = (91.0 + 21.0 * kR21) / 576.0, a96 = 11.0 / 72.0,
                 a97 = (-385.0 + 75.0 * kR21) / 1152.0, a98 = (63.0 - 13.0 * kR21) / 128.0;
constexpr double a101 = 1.0 / 14.0, a105 = 1.0 / 9.0, a106 = (-733.0 + 147.0 * kR21) / 2205.0,
                 a107 = (515.0 - 111.0 * kR21) / 504.0, a108 = (-51.0 + 11.0 * kR21) / 56.0,
                 a109 = (132.0 - 28.0 * kR21) / 245.0;
constexpr double a115 = (-42.0 - 7.0 * kR21) / 18.0, a116 = (-18.0 - 28.0 * kR21) / 45.0,
                 a117 = (-273.0 + 53.0 * kR21) / 72.0, a118 = (301.0 - 53.0 * kR21) / 72.0,
                 a119 = (28.0 + 28.0 * kR21) / 45.0, a1110 = (49.0 + 7.0 * kR21) / 18.0;
}  // namespace

void Integrator::Impl::rk8_step(const RhsFunction& f, double s, double h, double s_next,
                                const Eigen::VectorXd& y) {
  // c = 0, 1/2, 1/2, c4, c4, 1/2, c7, c7, 1/2, c4, 1 (c4, c7 = (7 -+ sqrt 21)/14);
  // b = 1/20, 0, 0, 0, 0, 0, 0, 49/180, 16/45, 49/180, 1/20.
  f(s, y, k1);
  y_stage = y + (0.5 * h) * k1;
  f(s + 0.5 * h, y_stage, k2);
  y_stage = y + (0.25 * h) * (k1 + k2);
  f(s + 0.5 * h, y_stage, k3);
  y_stage = y + h * (a41 * k1 + a42 * k2 + a43 * k3);
  f(s + kC4 * h, y_stage, k4);
  y_stage = y + h * (a51 * k1 + a53 * k3 + a54 * k4);
  f(s + kC4 * h, y_stage, k5);
  y_stage = y + h * (a61 * k1 + a63 * k3 + a64 * k4 + a65 * k5);
  f(s + 0.5 * h, y_stage, k6);
  y_stage = y + h * (a71 * k1 + a73 * k3 + a74 * k4 + a75 * k5 + a76 * k6);
  f(s + kC7 * h, y_stage, k7);
  y_stage = y + h * (a81 * k1 + a85 * k5 + a86 * k6 + a87 * k7);
  f(s + kC7 * h, y_stage, k8);
  y_stage = y + h * (a91 * k1 + a95 * k5 + a96 * k6 + a97 * k7 + a98 * k8);
  f(s + 0.5 * h, y_stage, k9);
  y_stage = y + h * (a101 * k1 + a105 * k5 + a106 * k6 + a107 * k7 + a108 * k8 + a109 * k9);
  f(s + kC4 * h, y_stage, k10);
  y_stage = y + h * (a115 * k5 + a116 * k6 + a117 * k7 + a118 * k8 + a119 * k9 + a1110 * k10);
  f(s_next, y_stage, k11);
  y_next = y + (h / 180.0) * (9.0 * (k1 + k11) + 49.0 * (k8 + k10) + 64.0 * k9);
}

Tableau tableau(Method m) {
  require(is_fixed_step(m), "method", to_string(m),
          "has no Butcher tableau (not a fixed-step method)");
  Tableau t;
  if (m == Method::kRk4) {
    t.stages = 4;
    t.a = {0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0};
    t.b = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  } else if (m == Method::kRk6) {
    t.stages = 7;
    t.a.assign(49, 0.0);
    const double rows[7][6] = {
        {0, 0, 0, 0, 0, 0},
        {1.0 / 3.0, 0, 0, 0, 0, 0},
        {0, 2.0 / 3.0, 0, 0, 0, 0},
        {1.0 / 12.0, 1.0 / 3.0, -1.0 / 12.0, 0, 0, 0},
        {-1.0 / 16.0, 9.0 / 8.0, -3.0 / 16.0, -3.0 / 8.0, 0, 0},
        {0, 9.0 / 8.0, -3.0 / 8.0, -3.0 / 4.0, 0.5, 0},
        {9.0 / 44.0, -9.0 / 11.0, 63.0 / 44.0, 18.0 / 11.0, 0, -16.0 / 11.0}};
    for (int i = 0; i < 7; ++i) {
      for (int j = 0; j < i; ++j) t.a[7 * i + j] = rows[i][j];
    }
    t.b = {11.0 / 120.0, 0, 27.0 / 40.0, 27.0 / 40.0, -4.0 / 15.0, -4.0 / 15.0, 11.0 / 120.0};
  } else {
    t.stages = 11;
    t.a.assign(121, 0.0);
    const auto set = [&t](int i, int j, double v) { t.a[11 * (i - 1) + (j - 1)] = v; };
    set(2, 1, 0.5);
    set(3, 1, 0.25), set(3, 2, 0.25);
    set(4, 1, a41), set(4, 2, a42), set(4, 3, a43);
    set(5, 1, a51), set(5, 3, a53), set(5, 4, a54);
    set(6, 1, a61), set(6, 3, a63), set(6, 4, a64), set(6, 5, a65);
    set(7, 1, a71), set(7, 3, a73), set(7, 4, a74), set(7, 5, a75), set(7, 6, a76);
    set(8, 1, a81), set(8, 5, a85), set(8, 6, a86), set(8, 7, a87);
    set(9, 1, a91), set(9, 5, a95), set(9, 6, a96), set(9, 7, a97), set(9, 8, a98);
    set(10, 1, a101), set(10, 5, a105), set(10, 6, a106), set(10, 7, a107), set(10, 8, a108);
    set(10, 9, a109);
    set(11, 5, a115), set(11, 6, a116), set(11, 7, a117), set(11, 8, a118), set(11, 9, a119);
    set(11, 10, a1110);
    t.b = {9.0 / 180.0, 0, 0, 0, 0, 0, 0, 49.0 / 180.0, 64.0 / 180.0, 49.0 / 180.0, 9.0 / 180.0};
  }
  // Nodes: the row sums (every tableau here satisfies c_i = sum_j a_ij).
  t.c.assign(t.stages, 0.0);
  for (int i = 0; i < t.stages; ++i) {
    for (int j = 0; j < i; ++j) t.c[i] += t.a[t.stages * i + j];
  }
  return t;
}

IntegrationSummary Integrator::Impl::integrate_fixed(const RhsFunction& f, double s0, double s1,
                                                     Eigen::VectorXd& y, const Observer& observer) {
  IntegrationSummary summary;
  const Method method = options.method;
  const int stages = method == Method::kRk8 ? 11 : method == Method::kRk6 ? 7 : 4;
  const int n_steps = options.steps;
  const int observe_every = options.output_intervals == 0 ? 1 : n_steps / options.output_intervals;
  const double h = (s1 - s0) / n_steps;
  summary.s_final = s0;
  if (observer) observer(s0, y);
  for (int i = 0; i < n_steps; ++i) {
    const double s = s0 + i * h;
    const double s_next = i + 1 == n_steps ? s1 : s0 + (i + 1) * h;
    if (method == Method::kRk8) {
      rk8_step(f, s, h, s_next, y);
    } else if (method == Method::kRk6) {
      rk6_step(f, s, h, s_next, y);
    } else {
      rk4_step(f, s, h, s_next, y);
    }
    summary.rhs_evaluations += stages;
    if (!y_next.allFinite()) {
      summary.status = IntegrationSummary::Status::kFailed;
      summary.message = fmt::format(
          "{}: the state became non-finite in step {} of {} (s = {} -> {}); y is left at s = {}",
          method == Method::kRk8   ? "RK8"
          : method == Method::kRk6 ? "RK6"
                                   : "RK4",
          i + 1, n_steps, s, s_next, s);
      return summary;
    }
    y = y_next;
    summary.steps = i + 1;
    summary.s_final = s_next;
    if (observer && (i + 1) % observe_every == 0) observer(s_next, y);
  }
  return summary;
}

IntegrationSummary Integrator::Impl::integrate_cvode(const RhsFunction& f, double s0, double s1,
                                                     Eigen::VectorXd& y, const Observer& observer) {
  IntegrationSummary summary;
  void* mem = cvode.get();
  rhs = &f;
  rhs_count = 0;
  rhs_exception = nullptr;
  last_cvode_message.clear();
  Eigen::Map<Eigen::VectorXd> y_cv(N_VGetArrayPointer(y_nv.get()), dimension);
  y_cv = y;
  check_cvode(CVodeReInit(mem, s0, y_nv.get()), "CVodeReInit");
  // Never step past s1: the RHS may be undefined beyond the end of the interval.
  check_cvode(CVodeSetStopTime(mem, s1), "CVodeSetStopTime");

  summary.s_final = s0;
  if (observer) observer(s0, y);
  const int M = options.output_intervals == 0 ? 1 : options.output_intervals;
  for (int k = 1; k <= M; ++k) {
    const double target = output_point(s0, s1, k, M);
    realtype reached = s0;
    const int flag = CVode(mem, target, y_nv.get(), &reached, CV_NORMAL);
    summary.rhs_evaluations = rhs_count;
    long n_steps = 0;
    check_cvode(CVodeGetNumSteps(mem, &n_steps), "CVodeGetNumSteps");
    summary.steps = n_steps;
    if (rhs_exception) {
      rhs = nullptr;
      std::rethrow_exception(std::exchange(rhs_exception, nullptr));
    }
    const bool finite = y_cv.allFinite();
    if (finite) {
      y = y_cv;
      summary.s_final = reached;
    }
    if (flag < 0 || !finite) {
      summary.status = IntegrationSummary::Status::kFailed;
      summary.message =
          flag < 0 ? fmt::format("CVODE returned {} at s = {} (target s = {}): {}",
                                 cvode_flag_name(flag), reached, target, last_cvode_message)
                   : fmt::format("CVODE: the state became non-finite at s = {}", reached);
      break;
    }
    if (observer && (options.output_intervals > 0 || k == M)) observer(target, y);
  }
  rhs = nullptr;
  return summary;
}

Integrator::Integrator(int dimension, const IntegratorOptions& options) {
  validate(dimension, options);
  impl_ = std::make_unique<Impl>(dimension, options);
}

Integrator::~Integrator() = default;
Integrator::Integrator(Integrator&&) noexcept = default;
Integrator& Integrator::operator=(Integrator&&) noexcept = default;

const IntegratorOptions& Integrator::options() const { return impl_->options; }
int Integrator::dimension() const { return impl_->dimension; }

IntegrationSummary Integrator::integrate(const RhsFunction& f, double s0, double s1,
                                         Eigen::VectorXd& y, const Observer& observer) {
  // Messages are only built on failure: integrate() is called thousands of times.
  if (!f) throw InputError("f", "empty", "must be a callable right-hand side");
  if (!std::isfinite(s0)) throw InputError("s0", format_value(s0), "must be finite");
  if (!(std::isfinite(s1) && s1 > s0))
    throw InputError("s1", format_value(s1), fmt::format("must be finite and > s0 = {}", s0));
  if (y.size() != impl_->dimension)
    throw InputError("y.size()", std::to_string(y.size()),
                     fmt::format("must equal the integrator dimension {}", impl_->dimension));
  if (!y.allFinite()) throw InputError("y", "(non-finite entries)", "must be finite at s0");
  return is_fixed_step(impl_->options.method) ? impl_->integrate_fixed(f, s0, s1, y, observer)
                                              : impl_->integrate_cvode(f, s0, s1, y, observer);
}

}  // namespace tcasim::ode
