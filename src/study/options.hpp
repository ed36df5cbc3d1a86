#pragma once
/// The options of the two front ends, the `tcasim` command line (flags) and the tcasim Python
/// module (keywords), each checked once here: the same bound, the same rule and the same
/// message from both, only the option's name differs ("--steps" / "steps", OptionNames).
///
/// An option the user did not give is std::nullopt or the field's documented default; a
/// value the user gave is always checked and never means "not given" (0 is a value).
#include <optional>
#include <string>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "common/error.hpp"
#include "common/ode.hpp"
#include "cosserat/shooting.hpp"
#include "method/method.hpp"
#include "rod/model.hpp"

namespace tcasim::study {

/// How option names appear in errors: "dt_s" (Python) or "--dt-s" (the command line).
enum class OptionNames { kPython, kFlags };

/// The name of option `key` (snake_case) in `style`.
std::string option_name(const std::string& key, OptionNames style);

/// Upper bounds of the counts, each with its reason.
/// Fixed steps of the shooting integrator (common/ode.hpp says why).
inline constexpr int kMaxSteps = ode::kMaxFixedSteps;
/// FE elements: quadratic elements reach round-off near 1000 elements on the shipped
/// scenarios (validate_convergence); 10000 keeps one solve within seconds and memory small.
inline constexpr int kMaxElements = 10000;
/// Worker threads of a sweep: more than this many is a typo, not a machine.
inline constexpr int kMaxJobs = 1024;
/// Points per sweep chunk: a sweep has at most a million points (common/grid.hpp).
inline constexpr long long kMaxSweepChunk = 1000000;
/// The most time steps a simulation takes (a typo in dt_s would otherwise run for days).
inline constexpr long long kMaxTimeSteps = 100000000;
/// Newton iterations per time step of the dynamics.
inline constexpr int kMaxNewtonIterations = 1000;

/// Rethrows an InputError a library raised for one of the front ends' options (key "steps",
/// or "dynamics.steps" from the dynamics' options) under the option's name in `style`; any
/// other error (a scenario key) unchanged. For the rules only the solver can check (a grid
/// too coarse for the time step, a temperature bound below the material's range).
[[noreturn]] void rethrow_under_option_name(const InputError& e, OptionNames style);

/// Requires lo <= value <= hi for the count called `name` as shown to the user
/// ("--steps = 1000000000 must be an integer in [1, 100000]").
void require_count(long long value, const std::string& name, long long lo, long long hi);

/// Checks the solver choice: "cosserat" or "fe" (InputError naming `method` in `style`).
void check_method(const std::string& method, OptionNames style);

/// A simulation option given by the user: its key (snake_case) and its value as given.
struct GivenOption {
  std::string key, value;
};

/// Refuses an option of the other method than `method` ("cosserat" or "fe"), not ignored:
/// cosserat's `steps`, `alpha` and fe's `elements`, `order`, `rho_inf` (InputError naming the
/// first one in `given` that does not apply, its value and the rule, e.g. "applies to --method
/// fe only (cosserat: --steps, --alpha)" in `style`).
void refuse_other_method_options(const std::string& method, const std::vector<GivenOption>& given,
                                 OptionNames style);

/// The shooting integrator as given: steps, scheme, rtol (each absent when not given).
struct ShootingChoice {
  std::optional<long long> steps;     ///< fixed steps, even, in [2, kMaxSteps]; default 100
  std::optional<std::string> scheme;  ///< "rk4" (default), "rk6" or "rk8"
  std::optional<double> rtol;         ///< CVODE's relative tolerance in (0, 1); excludes both
  bool no_planar = false;             ///< solve a planar problem as a 3-D one
};

/// The shooting options of a choice; InputError naming the option in `style`, its value and
/// the rule.
cosserat::Options shooting_options(const ShootingChoice& c, OptionNames style);

/// The FE discretization and linear solver as given (the defaults are the front ends').
struct FeChoice {
  long long elements = 16;              ///< in [1, kMaxElements]
  long long order = 2;                  ///< Lagrange order, 1 or 2
  std::string integration = "reduced";  ///< Gauss rule: "reduced" or "full"
  std::string linear_solver = "klu";    ///< "klu", "umfpack" or "sparselu"
};

/// The FE options of a choice; InputError naming the option in `style`.
beam_fe::Options fe_options(const FeChoice& c, OptionNames style);

/// The method `method` names ("cosserat" or "fe", checked) with its choice: the front ends'
/// one choice of method (method/method.hpp); InputError naming the option in `style`.
method::StaticOptions static_options(const std::string& method, const ShootingChoice& shooting,
                                     const FeChoice& fe, OptionNames style);

/// Checks the parallel options of a sweep: jobs in [1, kMaxJobs], chunk in [1, kMaxSweepChunk].
void check_sweep_jobs(long long jobs, long long chunk, OptionNames style);

/// Temperatures [degC] of `key` (a sweep's or a TCA curve's) -> K; InputError naming the key
/// and the first that is not finite or not above absolute zero.
std::vector<double> temperatures_K(const std::vector<double>& temperatures_degC,
                                   const std::string& key, OptionNames style);

/// The constant tension [N] of a TCA curve (`tcasim tca`, tcasim.tca_curve): exactly one of
/// tension_N [N] (finite) and load_g [g] (a hanging mass >= 0, F = -m g) must be given.
double tca_tension_N(const std::optional<double>& tension_N, const std::optional<double>& load_g,
                     OptionNames style);

/// Checks a bound on the TCA temperature [degC] (above absolute zero) and returns it in K;
/// NaN when absent (the material's maximum).
double max_temperature_K(const std::optional<double>& t_degC, OptionNames style);

/// Checks the grasp's mass_g [g] (> 0), friction (> 0) and fingers (>= 1).
void check_grasp_options(double mass_g, double friction, long long fingers, OptionNames style);

/// Splits `text` at each `delimiter` into its items, refusing an empty item: a leading,
/// doubled or trailing delimiter ("25:", "1,2,", ",1", "a,,b") or an empty text is an
/// InputError naming `name` and the value, with `rule` (the list's format) and which item is
/// empty.
std::vector<std::string> split_list(const std::string& text, char delimiter,
                                    const std::string& name, const std::string& rule);

/// Comma-separated actuator names -> model indices (all actuators for an empty text);
/// InputError naming `name` for an unknown, repeated or empty name ("tca0,").
std::vector<int> actuator_indices(const rod::RodModel& model, const std::string& names,
                                  const std::string& name);

}  // namespace tcasim::study
