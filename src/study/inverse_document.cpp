#include "study/inverse_document.hpp"

#include <cstddef>
#include <limits>

#include "common/units.hpp"
#include "cosserat/shooting.hpp"
#include "rod/result.hpp"

namespace tcasim::study {

namespace {

using json = nlohmann::json;

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

DocumentRun inverse_document(const rod::RodModel& model, const Eigen::Vector3d& target_m,
                             const cosserat::InverseOptions& options) {
  cosserat::ShootingSolver solver(model, cosserat::Options{});
  rod::Loads act = rod::Loads::from_model(model);
  // Start from rest: TCAs at ambient (their material's reference temperature).
  for (int i : options.actuators) {
    const rod::Actuator& a = model.actuators[i];
    if (a.drive.type == rod::Drive::Type::kTca) {
      act.set_temperature_K(i, a.drive.tca->material().reference_temperature_K);
    }
  }
  cosserat::Solution sol;
  const cosserat::InverseResult r =
      cosserat::solve_inverse(solver, model, target_m, options, act, sol);

  json j;
  j["schema"] = "tcasim.inverse/1";
  j["scenario"] = model.name;
  j["converged"] = r.converged();
  j["status"] = cosserat::to_string(r.status);
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["forward_solves"] = r.forward_solves;
  j["target_m"] = vec(target_m);
  j["tip"] = {{"position_m", vec(r.tip_position_W_m)}};
  j["distance_m"] = r.distance_m;
  json acts = json::array();
  for (std::size_t k = 0; k < r.actuators.size(); ++k) {
    const rod::Actuator& a = model.actuators[r.actuators[k]];
    json e{{"name", a.name}, {"at_bound", k < r.at_bound.size() && r.at_bound[k]}};
    const double v = k < static_cast<std::size_t>(r.values.size())
                         ? r.values[static_cast<Eigen::Index>(k)]
                         : std::numeric_limits<double>::quiet_NaN();
    if (a.drive.type == rod::Drive::Type::kTca) {
      e["temperature_degC"] = units::K_to_degC(v);
      // Coil contact of the solved state at the final temperatures.
      const std::size_t i = static_cast<std::size_t>(r.actuators[k]);
      if (i < sol.tensions_N.size()) {
        rod::ActuatorResult c(a.name, sol.tensions_N[i], sol.elongations_m[i]);
        rod::set_coil_contacts(a, act.actuators[i].segments, c);
        e["coils_closed"] = c.coils_closed;
        e["contact_force_N"] = c.contact_force_N;
      }
    } else {
      e["tension_N"] = v;
    }
    acts.push_back(e);
  }
  j["actuators"] = acts;
  // With obstacles: the contact forces of the final state (the keys of a result file).
  if (!model.obstacles.empty() && sol.valid) {
    const cosserat::Summary s = solver.solve(act, sol);  // warm: the state itself
    if (s.converged()) {
      const json res = rod::to_json(solver.make_result(act, sol, s));
      for (const char* key : {"contacts", "contact_model", "base_reaction"}) {
        if (res.contains(key)) j[key] = res[key];
      }
    }
  }
  return {std::move(j), r.converged(), cosserat::to_string(r.status), r.message};
}

DocumentRun grasp_document(const rod::RodModel& model, double mass_g, double friction, int fingers,
                           double max_temperature_K) {
  cosserat::GraspOptions o;
  o.mass_kg = units::g_to_kg(mass_g);
  o.friction = friction;
  o.fingers = fingers;
  o.max_temperature_K = max_temperature_K;
  cosserat::Options so;
  so.tolerance = 1e-12;  // the blocked force is checked to 1e-9 relative
  const cosserat::GraspResult r = cosserat::solve_grasp(model, so, o);

  json j;
  j["schema"] = "tcasim.grasp/1";
  j["scenario"] = model.name;
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["mass_g"] = mass_g;
  j["friction"] = friction;
  j["fingers"] = fingers;
  j["temperature_degC"] = units::K_to_degC(r.temperature_K);
  j["normal_force_N"] = r.required_force_N;
  j["blocked_normal_force_N"] = r.blocked_normal_force_N;
  j["root_temperature_degC"] =
      r.root_temperature_K ? json(units::K_to_degC(*r.root_temperature_K)) : json();
  j["iterations"] = r.iterations;
  j["tip"] = {{"position_m", vec(r.tip_position_W_m)}};
  return {std::move(j), r.converged, r.converged ? "converged" : "not converged", r.message};
}

}  // namespace tcasim::study
