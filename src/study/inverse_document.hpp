#pragma once
/// The inverse and grasp runs of `tcasim inverse` / `tcasim grasp` and of the Python module's
/// tcasim.inverse / tcasim.grasp, each with its result document (schemas tcasim.inverse/1 and
/// tcasim.grasp/1, docs/scenario-format.md): one function builds what both front ends write,
/// so the CLI file and the Python dict hold the same numbers.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "cosserat/inverse.hpp"
#include "rod/model.hpp"

namespace tcasim::study {

/// A finished run: the document and its convergence (also in the document).
struct DocumentRun {
  nlohmann::json document;
  bool converged = false;
  std::string status;  ///< inverse: to_string(InverseResult::Status); grasp: (not) converged
  std::string message;
};

/// The target solve of `tcasim inverse`: default shooting options, every adjusted TCA
/// starting from rest (its material's reference temperature), cosserat::solve_inverse. The
/// model must have a free tip. InputError (from solve_inverse) for bad options.
DocumentRun inverse_document(const rod::RodModel& model, const Eigen::Vector3d& target_m,
                             const cosserat::InverseOptions& options);

/// The grasp temperature of `tcasim grasp`: cosserat::solve_grasp at a shooting tolerance of
/// 1e-12 (the blocked force is checked to 1e-9 relative) for the mass [g], friction and finger
/// count given, which the document repeats; max_temperature_K NaN: the material's maximum.
DocumentRun grasp_document(const rod::RodModel& model, double mass_g, double friction, int fingers,
                           double max_temperature_K);

}  // namespace tcasim::study
