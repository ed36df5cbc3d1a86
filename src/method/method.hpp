#pragma once
/// The one place that chooses between the two forward methods: the Cosserat rod solved by
/// shooting (cosserat/) and the Simo-Reissner beam elements (beam_fe/). A caller (a sweep, a
/// cross-check, a simulation, the command line, Python) holds the method's options in a
/// variant and calls StaticSolver / DynamicSolver (method/dynamics.hpp), which have one call
/// shape for both; it never branches on the method itself. The two discretizations and their
/// nonlinear strategies stay independent: this layer only dispatches.
#include <memory>
#include <string>
#include <variant>

#include "beam_fe/beam_fe.hpp"
#include "cosserat/shooting.hpp"
#include "rod/loads.hpp"
#include "rod/model.hpp"
#include "rod/result.hpp"

namespace tcasim::method {

/// A forward static method with its settings: the shooting solver's options or the FE's.
using StaticOptions = std::variant<cosserat::Options, beam_fe::Options>;

/// "cosserat" or "fe" (the result file's `method`).
const char* name(const StaticOptions& options);

/// The forward statics of one model by either method. Each solve warm-starts from the last
/// converged one of this object (a cold start on the first solve and after reset()): what a
/// sweep does along its points. Holds a reference to the model, which must outlive it; not
/// thread-safe (one per thread). The constructor validates the options (InputError naming
/// the field); a solve validates the loads (InputError) and never throws for
/// non-convergence: the result then says converged = false, with the status and why.
class StaticSolver {
 public:
  StaticSolver(const rod::RodModel& model, const StaticOptions& options);
  ~StaticSolver();
  StaticSolver(StaticSolver&&) noexcept;
  StaticSolver& operator=(StaticSolver&&) noexcept;
  StaticSolver(const StaticSolver&) = delete;
  StaticSolver& operator=(const StaticSolver&) = delete;

  /// Solves under `loads` and returns the result file record (rod/result.hpp).
  rod::Result solve(const rod::Loads& loads);
  /// Forgets the last solution: the next solve starts cold.
  void reset();
  /// "cosserat" or "fe".
  const char* method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One solve of the model's own loads by the chosen method: StaticSolver(model,
/// options).solve(rod::Loads::from_model(model)).
rod::Result solve(const rod::RodModel& model, const StaticOptions& options);

}  // namespace tcasim::method
