// validate_contact: the rod's contact with rigid obstacles (rod/obstacle.hpp), both static
// methods (Cosserat shooting, beam FE) through method::StaticSolver, against closed forms,
// an independent planar reference, global equilibrium and each other.
//
// What it checks (docs/validation.md "validate_contact")
//   Step 1  heavy rod on a floor (validation/scenarios/contact/heavy-rod-floor.json, the floor
//           moved to gaps H): clamp force and moment of both methods on refinement ladders
//           (shooting `steps`, FE `elements`) against the small-slope closed form
//           (rod::heavy_rod_on_floor) and against a planar Cosserat reference with touchdown
//           solved here (RK4 shooting of the extensible, shearable planar rod with
//           K = diag(GA, EA, EI), the law both solvers use), which measures the closed form's
//           own small-slope error.
//   Step 2  propped cantilever (propped-cantilever-sphere.json): the sphere's reaction against
//           P (3 L - a) / (2 a).
//   Step 3  global balance of every solve with obstacles (and of two without): base_reaction
//           + weight + tip loads + contact resultants = 0, forces and moments about the base.
//   Step 4  cross-method agreement on the contact suite: tip position and contact resultant of
//           the finest shooting and FE solves on refinement ladders.
//   Step 5  sweeps across contact onset with warm starts: a cantilever tangent to a cylinder
//           under a rising tip force (against rod::cantilever_on_cylinder), and the TCA finger
//           heating onto its peg (tca-finger-cylinder.json).
// Tolerances (no constant is tuned to pass; each bound is derived, see the gates)
//   - discretization: the last change of a ladder, |X_f - X_(f-1)|, bounds the finest level's
//     error for any order >= 1 in the asymptotic range (error_f ~ change / (2^p - 1));
//   - small slope: measured, |planar reference - closed form|, which is O(theta^2);
//   - balance: the solver's reported residual (largest nodal unbalance over F_c) summed over
//     its nodes, plus the quadrature error of the weight's moment from the centerline samples;
//   - cross-method: the sum of the two ladders' last changes, plus what the stopping tests
//     leave (residual force times the clamped rod's largest compliance L^3 / (3 B_min));
//   - penetration: the finest level's at most the coarsest's plus the solver's gap tolerance;
//   - small-slope references: the neglected terms are computed (planar references, the
//     contact point's travel, Timoshenko shear), not assumed;
//   - continuity after onset: halving the load step must shrink the largest increment of the
//     contact force between points in contact (a Lipschitz function halves it, a jump keeps
//     it): the gate is the midpoint 0.75.
// A solver that does not converge, throws, or returns no contact or base reaction fails its
// gate with the solver's message; the program never stops on it.
// Usage
//   validate_contact --out-dir out/contact            (full)
//   validate_contact --quick --out-dir /tmp/contact   (one gap, two levels per ladder; seconds)
//   /usr/bin/python3 scripts/plot_contact.py out/contact
#include <fmt/format.h>
#include <fmt/ostream.h>

#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "method/method.hpp"
#include "rod/closed_form.hpp"
#include "rod/loads.hpp"
#include "rod/output_file.hpp"
#include "rod/scenario.hpp"
#include "validation/common/gates.hpp"

namespace {

namespace rod = tcasim::rod;
namespace method = tcasim::method;
using Eigen::Vector3d;
using tcasim::validation::Gates;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kEps = std::numeric_limits<double>::epsilon();
/// The continuity gate: the largest contact-force increment with half the load step over the
/// one with the full step; a Lipschitz curve gives 0.5, a jump 1, the gate takes the midpoint.
constexpr double kContinuityRatio = 0.75;

// ------------------------------------------------------------------------------------------
// Solving without ever stopping the program.

/// One solve's outcome: the result, whether it can be used, and why not.
struct Outcome {
  rod::Result result;
  bool ok = false;
  std::string message;  ///< the solver's status and message, or the exception's text
  double time_s = 0.0;
};

Outcome solve_safely(method::StaticSolver& solver, const rod::Loads& loads) {
  Outcome o;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    o.result = solver.solve(loads);
    o.ok = o.result.converged;
    o.message = o.ok ? "" : o.result.status + ": " + o.result.message;
  } catch (const std::exception& e) {
    o.ok = false;
    o.message = std::string("exception: ") + e.what();
  }
  o.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return o;
}

/// One cold solve of `model` under `loads`.
Outcome solve_once(const rod::RodModel& model, const method::StaticOptions& options,
                   const rod::Loads& loads) {
  try {
    method::StaticSolver solver(model, options);
    return solve_safely(solver, loads);
  } catch (const std::exception& e) {
    Outcome o;
    o.message = std::string("exception: ") + e.what();
    return o;
  }
}

/// A refinement ladder of one method: shooting RK4 steps or quadratic FE elements.
struct Ladder {
  std::string method;  ///< "cosserat" or "fe"
  std::vector<int> levels;
  method::StaticOptions options(int level) const {
    if (method == "cosserat") {
      tcasim::cosserat::Options o;
      o.integrator.method = tcasim::ode::Method::kRk4;
      o.integrator.steps = level;
      return o;
    }
    tcasim::beam_fe::Options o;
    o.elements = level;
    o.order = 2;
    return o;
  }
  const char* level_name() const { return method == "cosserat" ? "steps" : "elements"; }
};

std::vector<Ladder> ladders(bool quick) {
  if (quick) return {{"cosserat", {100, 200}}, {"fe", {16, 32}}};
  return {{"cosserat", {100, 200, 400, 800, 1600}}, {"fe", {16, 32, 64, 128, 256}}};
}

// ------------------------------------------------------------------------------------------
// What a result says about contact.

/// The sum over the obstacles of a result's contacts.
struct ContactTotal {
  bool reported = false;  ///< the result has one contacts entry per model obstacle
  bool touching = false;  ///< some obstacle has a region
  Vector3d force_W_N = Vector3d::Zero();
  Vector3d moment_W_Nm = Vector3d::Zero();
  double first_s_m = kNaN;  ///< start of the first region of any obstacle
  double max_penetration_m = 0.0;
};

ContactTotal contact_total(const rod::RodModel& model, const rod::Result& r) {
  ContactTotal t;
  t.reported = !model.obstacles.empty() && r.contacts.size() == model.obstacles.size();
  for (const rod::ContactResult& c : r.contacts) {
    t.force_W_N += c.force_W_N;
    t.moment_W_Nm += c.moment_W_Nm;
    t.max_penetration_m = std::max(t.max_penetration_m, c.max_penetration_m);
    if (c.in_contact()) {
      t.touching = true;
      const double s0 = c.regions.front().s0_m;
      t.first_s_m = std::isnan(t.first_s_m) ? s0 : std::min(t.first_s_m, s0);
    }
  }
  return t;
}

/// Total weight of the body, int psi A g ds (composite Simpson on 4096 intervals: exact for a
/// mass per length that is quadratic in s, as a circle with a linear diameter profile).
Vector3d body_weight_W_N(const rod::RodModel& m, const rod::Loads& loads) {
  const int n = 4096;
  const double h = m.length_m / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * m.mass_per_length_kg_m(k * h, k == n ? rod::Side::kLeft : rod::Side::kRight);
  }
  return sum * h / 3.0 * loads.applied(m).gravity_W_m_s2;
}

/// Global balance of one solve (forces and moments about the base point, world frame).
struct Balance {
  bool has_base_reaction = false;
  Vector3d force_N = Vector3d::Zero();    ///< base + weight + tip + contacts
  Vector3d moment_Nm = Vector3d::Zero();  ///< about the base point
  double force_bound_N = 0.0;
  double moment_bound_Nm = 0.0;
  double weight_moment_quadrature_Nm = 0.0;  ///< |T_h - T_2h| of the weight's moment
};

/// The weight's moment about the base from the centerline samples (trapezoid), and the
/// difference to the same rule on every second sample (its error estimate).
std::pair<Vector3d, double> weight_moment(const rod::RodModel& m, const rod::Loads& loads,
                                          const rod::Result& r) {
  const Vector3d g = loads.applied(m).gravity_W_m_s2;
  const Vector3d& p0 = m.base_position_W_m;
  auto trapezoid = [&](int stride) {
    Vector3d sum = Vector3d::Zero();
    const int n = static_cast<int>(r.centerline_s_m.size());
    int prev = 0;
    for (int k = stride; k < n + stride - 1; k += stride) {
      const int i = std::min(k, n - 1);
      const double ds = r.centerline_s_m[i] - r.centerline_s_m[prev];
      const Vector3d fa =
          (r.centerline_p_W_m[prev] - p0).cross(m.mass_per_length_kg_m(r.centerline_s_m[prev]) * g);
      const Vector3d fb =
          (r.centerline_p_W_m[i] - p0)
              .cross(m.mass_per_length_kg_m(r.centerline_s_m[i], rod::Side::kLeft) * g);
      sum += 0.5 * ds * (fa + fb);
      prev = i;
      if (i == n - 1) break;
    }
    return sum;
  };
  if (r.centerline_s_m.size() < 3) return {Vector3d::Zero(), kNaN};
  const Vector3d fine = trapezoid(1);
  return {fine, (fine - trapezoid(2)).norm()};
}

/// `stop_tolerance`: the scaled residual the method's stopping test accepts on top of the
/// reported one (the shooting stops on its tip residual <= tolerance x F_c, a force at the
/// tip that the reported nodal residual need not show; 0 for the FE, whose test is on the
/// nodal residuals it reports).
Balance balance(const rod::RodModel& m, const rod::Loads& loads, const rod::Result& r,
                double stop_tolerance) {
  Balance b;
  b.has_base_reaction = r.base_reaction.has_value();
  const rod::Loads applied = loads.applied(m);
  const Vector3d& p0 = m.base_position_W_m;
  const Vector3d tip_force = rod::tip_force_with_weight_W_N(m, applied);
  const Vector3d weight = body_weight_W_N(m, loads);
  const ContactTotal c = contact_total(m, r);
  const auto [w_moment, w_quadrature] = weight_moment(m, loads, r);
  const Vector3d base_f = b.has_base_reaction ? r.base_reaction->force_W_N : Vector3d::Zero();
  const Vector3d base_m = b.has_base_reaction ? r.base_reaction->moment_W_Nm : Vector3d::Zero();
  const Vector3d tip_arm = r.tip_position_W_m - p0;
  Vector3d tip_reaction = r.tip_reaction_force_W_N.value_or(Vector3d::Zero());
  b.force_N = base_f + weight + tip_force + tip_reaction + c.force_W_N;
  b.moment_Nm = base_m + w_moment + applied.tip_moment_W_Nm + tip_arm.cross(tip_force) +
                tip_arm.cross(tip_reaction) + c.moment_W_Nm;
  // Bounds: the solver's remaining unbalance, at most its residual (largest nodal
  // unbalance over F_c, moments over L) at every centerline sample, plus the round-off of
  // summing the terms.
  const double Fc = r.characteristic_force_N;
  const double n = static_cast<double>(std::max<std::size_t>(r.centerline_s_m.size(), 1));
  const double terms =
      base_f.norm() + weight.norm() + tip_force.norm() + tip_reaction.norm() + c.force_W_N.norm();
  const double residual = r.residual.value_or(kNaN);
  b.force_bound_N = (n * residual + stop_tolerance) * Fc + 1e3 * kEps * terms;
  b.weight_moment_quadrature_Nm = w_quadrature;
  b.moment_bound_Nm = (n * residual + stop_tolerance) * Fc * m.length_m +
                      1e3 * kEps * terms * m.length_m + (weight.norm() > 0.0 ? w_quadrature : 0.0);
  return b;
}

// ------------------------------------------------------------------------------------------
// The planar reference of the heavy rod on a floor.

/// The heavy rod's free span as a planar Cosserat rod (extensible, shearable; K = diag(GA,
/// EA, EI)), clamped horizontally at gap H, touching down at s = l with zero gap, zero slope
/// and zero moment (the flat part beyond carries nothing). Internal force n (of the distal
/// part on the proximal one): horizontal 0 (frictionless floor, free end), vertical n0 + q s.
/// Unknowns n0, m0, l; RK4 in `steps` steps; Newton with a difference Jacobian.
struct PlanarReference {
  bool ok = false;
  double free_span_m = kNaN, base_force_N = kNaN, base_moment_Nm = kNaN;
  double touchdown_force_N = kNaN, max_slope = kNaN;
};

PlanarReference heavy_rod_planar(double EI, double EA, double GA, double q, double H, int steps) {
  // y = (X, Y, theta, m); Y the height of the lowest surface line above the floor at
  // theta = 0 (centerline height - floor - r), so touchdown is Y = 0 with theta = 0.
  auto run = [&](const Eigen::Vector3d& u, double* max_slope) {
    const double n0 = u[0], m0 = u[1], l = u[2];
    const double h = l / steps;
    Eigen::Vector4d y(0.0, H, 0.0, m0);
    auto f = [&](double s, const Eigen::Vector4d& v) {
      const double nY = n0 + q * s;
      const double c = std::cos(v[2]), sn = std::sin(v[2]);
      const double nt = sn * nY, nn = c * nY;  // along the section normal t and across it
      const double stretch = 1.0 + nt / EA, shear = nn / GA;
      Eigen::Vector4d d;
      d[0] = stretch * c - shear * sn;
      d[1] = stretch * sn + shear * c;
      d[2] = v[3] / EI;
      d[3] = -(d[0] * nY);  // m' = -(p' x n)_z, n = (0, nY)
      return d;
    };
    double slope = 0.0;
    for (int k = 0; k < steps; ++k) {
      const double s = k * h;
      const Eigen::Vector4d k1 = f(s, y), k2 = f(s + h / 2, y + h / 2 * k1);
      const Eigen::Vector4d k3 = f(s + h / 2, y + h / 2 * k2), k4 = f(s + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      slope = std::max(slope, std::abs(std::tan(y[2])));
    }
    if (max_slope) *max_slope = slope;
    return Eigen::Vector3d(y[1], y[2], y[3]);
  };
  const rod::HeavyRodOnFloor cf = rod::heavy_rod_on_floor(EI, q, H);
  Eigen::Vector3d u(-cf.base_force_N, -cf.base_moment_Nm, cf.free_span_m);
  const Eigen::Vector3d scale(cf.base_force_N, cf.base_moment_Nm, cf.free_span_m);
  PlanarReference ref;
  for (int it = 0; it < 30; ++it) {
    const Eigen::Vector3d r = run(u, nullptr);
    const Eigen::Vector3d r_scaled(r[0] / H, r[1] / cf.max_slope, r[2] / cf.base_moment_Nm);
    if (r_scaled.lpNorm<Eigen::Infinity>() < 1e-13) {
      ref.ok = true;
      break;
    }
    Eigen::Matrix3d J;
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d du = Eigen::Vector3d::Zero();
      du[j] = 1e-7 * scale[j];
      const Eigen::Vector3d a = run(u + du, nullptr), b = run(u - du, nullptr);
      J.col(j) = (a - b) / (2.0 * du[j]);
    }
    u -= J.partialPivLu().solve(r);
  }
  double slope = kNaN;
  const Eigen::Vector3d r = run(u, &slope);
  ref.ok = ref.ok || (std::abs(r[0]) < 1e-12 * H && std::abs(r[2]) < 1e-12 * cf.base_moment_Nm);
  ref.base_force_N = -u[0];
  ref.base_moment_Nm = std::abs(u[1]);
  ref.free_span_m = u[2];
  ref.touchdown_force_N = u[0] + q * u[2];
  ref.max_slope = slope;
  return ref;
}

// ------------------------------------------------------------------------------------------

std::string level_label(const Ladder& l, int level) {
  return fmt::format("{} {} {}", l.method, level, l.level_name());
}

/// Relative difference |a - b| / |b|.
double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// Observed order from three successive errors on a ladder of ratio 2 (NaN when undefined).
double order_of(double e_coarse, double e_fine) {
  return (e_coarse > 0.0 && e_fine > 0.0) ? std::log2(e_coarse / e_fine) : kNaN;
}

std::string fmt_vec(const Vector3d& v) {
  return fmt::format("{:.6e},{:.6e},{:.6e}", v.x(), v.y(), v.z());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Contact with rigid obstacles: closed forms, balance, cross-method agreement"};
  bool quick = false;
  std::string out_dir = "contact-out";
  std::string scenario_dir = std::string(TCASIM_SCENARIO_DIR) + "/contact";
  app.add_flag("--quick", quick, "one gap, two levels per ladder (seconds)");
  app.add_option("--out-dir", out_dir, "output folder for CSV files");
  app.add_option("--scenario-dir", scenario_dir, "folder with the contact suite");
  CLI11_PARSE(app, argc, argv);

  try {
    const auto t_start = std::chrono::steady_clock::now();
    auto elapsed = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    };
    auto progress = [&](const std::string& what) {
      fmt::print("  [{:7.2f} s] {}\n", elapsed(), what);
      std::fflush(stdout);
    };
    std::filesystem::create_directories(out_dir);
    Gates gates("validate_contact");
    const std::vector<Ladder> all_ladders = ladders(quick);

    // The suite, by name (contact_scenarios_test.cpp holds the same list).
    const std::vector<std::string> suite = {"heavy-rod-floor",        "propped-cantilever-sphere",
                                            "tca-finger-cylinder",    "gripper-finger-wall",
                                            "soft-rod-floor",         "three-tca-sphere",
                                            "rectangle-plane-corner", "tapered-tentacle-box"};
    std::map<std::string, rod::RodModel> models;
    fmt::print("Step 0: contact suite ({})\n", scenario_dir);
    for (const std::string& name : suite) {
      const std::string path = scenario_dir + "/" + name + ".json";
      try {
        models.emplace(name, rod::read_scenario(path));
        progress(fmt::format("{}: {} obstacle(s)", name, models.at(name).obstacles.size()));
      } catch (const std::exception& e) {
        gates.not_run(name, std::string("cannot read: ") + e.what());
      }
    }
    gates.expect_count("contact scenarios read", models.size(), suite.size());

    // --------------------------------------------------------------------------------------
    fmt::print("Step 1: heavy rod on a floor against the closed form and the planar reference\n");
    {
      tcasim::rod::AtomicOutput csv(out_dir + "/heavy_rod.csv", "heavy rod csv");
      csv << "H_m,max_slope,method,level,converged,base_force_N,base_moment_Nm,touchdown_s_m,"
             "contact_force_z_N,closed_base_force_N,closed_base_moment_Nm,closed_free_span_m,"
             "ref_base_force_N,ref_base_moment_Nm,ref_free_span_m,force_error_vs_closed,"
             "moment_error_vs_closed,force_error_vs_ref,moment_error_vs_ref,force_change,"
             "moment_change,observed_order_moment,time_s,message\n";
      tcasim::rod::AtomicOutput small(out_dir + "/heavy_rod_small_slope.csv", "small slope csv");
      small << "H_m,max_slope,closed_free_span_m,ref_free_span_m,closed_base_force_N,"
               "ref_base_force_N,closed_base_moment_Nm,ref_base_moment_Nm,force_error,"
               "moment_error,moment_error_over_slope2,elastica_base_moment_Nm,"
               "geometric_moment_error,geometric_force_error,geometric_force_error_over_slope2,"
               "shear_extension_moment_effect,ref_converged\n";
      tcasim::rod::AtomicOutput shape(out_dir + "/heavy_rod_shape.csv", "heavy rod shape csv");
      shape << "H_m,method,level,s_m,x_m,z_m\n";
      tcasim::rod::AtomicOutput params(out_dir + "/heavy_rod_params.csv", "heavy rod params");
      params << "H_m,B_N_m2,q_N_m,radius_m,floor_z_m,length_m,closed_free_span_m\n";
      const auto it = models.find("heavy-rod-floor");
      if (it == models.end()) {
        gates.not_run("step 1 heavy rod", "heavy-rod-floor.json was not read");
      } else {
        const rod::RodModel& base = it->second;
        const double r = 0.5 * base.section.properties_at(0.0).width_m;
        const rod::SectionStiffness K = base.stiffness_at(0.0);
        const double EI = K.bending_torsion.x(), EA = K.shear_extension.z();
        const double GA = K.shear_extension.x();
        const double q = base.mass_per_length_kg_m(0.0) * base.gravity_W_m_s2.norm();
        const std::vector<double> gaps =
            quick ? std::vector<double>{0.0025} : std::vector<double>{0.010, 0.0025, 0.000625};
        std::vector<double> closed_error_force, slopes;
        for (double H : gaps) {
          rod::RodModel m = base;
          m.obstacles.at(0).point_W_m.z() = m.base_position_W_m.z() - r - H;
          const rod::HeavyRodOnFloor cf = rod::heavy_rod_on_floor(EI, q, H);
          const PlanarReference ref = heavy_rod_planar(EI, EA, GA, q, H, 4000);
          const PlanarReference ref_half = heavy_rod_planar(EI, EA, GA, q, H, 2000);
          // The same rod without shear and extension (Kirchhoff elastica, EA = GA = inf):
          // its distance to the closed form is the geometric (small-slope) error alone; the
          // rest, reference - elastica, is the shear and extension the closed form leaves out.
          const double inf = std::numeric_limits<double>::infinity();
          const PlanarReference elastica = heavy_rod_planar(EI, inf, inf, q, H, 4000);
          fmt::print(
              "  H = {:.4g} m: closed form l = {:.6f} m, F = {:.6e} N, M = {:.6e} N m, slope "
              "{:.3e}; planar reference l = {:.6f} m, F = {:.6e} N, M = {:.6e} N m ({}); "
              "elastica M = {:.6e} N m\n",
              H, cf.free_span_m, cf.base_force_N, cf.base_moment_Nm, cf.max_slope, ref.free_span_m,
              ref.base_force_N, ref.base_moment_Nm, ref.ok ? "converged" : "NOT converged",
              elastica.base_moment_Nm);
          gates.check(fmt::format("heavy rod H = {:.4g} m: planar references converge", H),
                      ref.ok && ref_half.ok && elastica.ok,
                      fmt::format("{} / {} / {} (4000 / 2000 RK4 steps; elastica)", ref.ok,
                                  ref_half.ok, elastica.ok),
                      "all");
          // Its own RK4 error, 1/15 of the change from 2000 steps, far below the errors below.
          const double ref_error = rel(ref.base_moment_Nm, ref_half.base_moment_Nm) / 15.0;
          const double small_slope_f = rel(cf.base_force_N, ref.base_force_N);
          const double small_slope_m = rel(cf.base_moment_Nm, ref.base_moment_Nm);
          const double geometric_m = rel(cf.base_moment_Nm, elastica.base_moment_Nm);
          const double geometric_f = rel(cf.base_force_N, elastica.base_force_N);
          const double shear_m = rel(elastica.base_moment_Nm, ref.base_moment_Nm);
          closed_error_force.push_back(geometric_f);
          // The elastica has a first integral, m^2 / (2 B) + n_Y sin(theta) - q Y = const
          // (d/ds: m theta' + q sin(theta) (s-derivative of n_Y) + n_Y cos(theta) theta' - q
          // sin(theta), zero by m' = -cos(theta) n_Y), zero at touchdown; at the clamp
          // (theta = 0, Y = H) it gives M = sqrt(2 B q H) = q l^2 / 6 exactly, at any slope.
          // The closed form's clamp moment is therefore exact for the elastica: a check of the
          // planar reference, to its RK4 error and round-off.
          const PlanarReference elastica_half = heavy_rod_planar(EI, inf, inf, q, H, 2000);
          const double exact_m = std::sqrt(2.0 * EI * q * H);
          gates.at_most(
              fmt::format("heavy rod H = {:.4g} m: elastica clamp moment vs its first "
                          "integral sqrt(2 B q H), relative (bound: RK4 change / 15 "
                          "+ 1e3 eps)",
                          H),
              rel(elastica.base_moment_Nm, exact_m),
              rel(elastica.base_moment_Nm, elastica_half.base_moment_Nm) / 15.0 + 1e3 * kEps);
          slopes.push_back(cf.max_slope);
          fmt::print(small,
                     "{},{:.6e},{:.10e},{:.10e},{:.10e},{:.10e},{:.10e},{:.10e},{:.6e},"
                     "{:.6e},{:.6e},{:.10e},{:.6e},{:.6e},{:.6e},{:.6e},{}\n",
                     H, cf.max_slope, cf.free_span_m, ref.free_span_m, cf.base_force_N,
                     ref.base_force_N, cf.base_moment_Nm, ref.base_moment_Nm, small_slope_f,
                     small_slope_m, small_slope_m / (cf.max_slope * cf.max_slope),
                     elastica.base_moment_Nm, geometric_m, geometric_f,
                     geometric_f / (cf.max_slope * cf.max_slope), shear_m, ref.ok);
          fmt::print(params, "{},{:.10e},{:.10e},{:.6e},{:.10e},{},{:.10e}\n", H, EI, q, r,
                     m.obstacles.at(0).point_W_m.z(), m.length_m, cf.free_span_m);
          for (const Ladder& lad : all_ladders) {
            std::vector<Outcome> outs;
            for (int level : lad.levels) {
              progress(fmt::format("heavy rod H = {:.4g} m, {}", H, level_label(lad, level)));
              outs.push_back(solve_once(m, lad.options(level), rod::Loads::from_model(m)));
            }
            // Errors along the ladder.
            double prev_f = kNaN, prev_m = kNaN, prev_change_m = kNaN;
            std::vector<double> changes_m;
            for (std::size_t k = 0; k < outs.size(); ++k) {
              const Outcome& o = outs[k];
              const ContactTotal c = contact_total(m, o.result);
              const bool usable = o.ok && o.result.base_reaction.has_value();
              const double F = usable ? o.result.base_reaction->force_W_N.z() : kNaN;
              const double M = usable ? o.result.base_reaction->moment_W_Nm.norm() : kNaN;
              const double change_f = std::abs(F - prev_f), change_m = std::abs(M - prev_m);
              const double p = order_of(prev_change_m, change_m);
              fmt::print(csv,
                         "{},{:.6e},{},{},{},{:.10e},{:.10e},{:.6e},{:.10e},{:.10e},{:.10e},"
                         "{:.10e},{:.10e},{:.10e},{:.10e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},"
                         "{:.6e},{:.4f},{:.3f},\"{}\"\n",
                         H, cf.max_slope, lad.method, lad.levels[k], o.ok ? 1 : 0, F, M,
                         c.first_s_m, c.force_W_N.z(), cf.base_force_N, cf.base_moment_Nm,
                         cf.free_span_m, ref.base_force_N, ref.base_moment_Nm, ref.free_span_m,
                         rel(F, cf.base_force_N), rel(M, cf.base_moment_Nm),
                         rel(F, ref.base_force_N), rel(M, ref.base_moment_Nm), change_f, change_m,
                         p, o.time_s, o.message);
              prev_f = F;
              prev_m = M;
              if (k > 0) changes_m.push_back(change_m);
              prev_change_m = change_m;
            }
            const std::string what = fmt::format("heavy rod H = {:.4g} m / {}", H, lad.method);
            int failed = 0;
            std::string why;
            for (const Outcome& o : outs) {
              if (!o.ok) {
                ++failed;
                if (why.empty()) why = o.message;
              }
            }
            gates.check(
                what + ": every solve converges", failed == 0,
                failed == 0 ? std::string("0 failed") : fmt::format("{} failed: {}", failed, why),
                "0");
            const Outcome& finest = outs.back();
            const ContactTotal c = contact_total(m, finest.result);
            gates.check(
                what + ": the floor is touched and base_reaction reported (finest)",
                finest.ok && c.reported && c.touching && finest.result.base_reaction.has_value(),
                fmt::format("contacts {}, touching {}, base_reaction {}",
                            c.reported ? "reported" : "missing", c.touching,
                            finest.result.base_reaction ? "reported" : "missing"),
                "all");
            if (outs.size() >= 2 && finest.ok && finest.result.base_reaction) {
              const Outcome& prev = outs[outs.size() - 2];
              const double F = finest.result.base_reaction->force_W_N.z();
              const double M = finest.result.base_reaction->moment_W_Nm.norm();
              const double dF = prev.result.base_reaction
                                    ? std::abs(F - prev.result.base_reaction->force_W_N.z())
                                    : kNaN;
              const double dM = prev.result.base_reaction
                                    ? std::abs(M - prev.result.base_reaction->moment_W_Nm.norm())
                                    : kNaN;
              // Against the planar reference: within the last change of the ladder, the
              // reference's own error, and the part of the reference it knows only to its
              // order of magnitude: its shear and extension (reference - elastica). It
              // touches down with a point force and theta(l) = 0, exact for the elastica;
              // a shearable rod has a boundary layer there, of length sqrt(E I / (G A)),
              // where the shear strain R / (G A) of the touchdown force turns the section
              // (the solvers satisfy the gap at their nodes, not this end condition).
              const double shear_M = std::abs(ref.base_moment_Nm - elastica.base_moment_Nm);
              const double shear_F = std::abs(ref.base_force_N - elastica.base_force_N);
              gates.at_most(what +
                                ": clamp moment vs planar reference (bound: last ladder "
                                "change + reference error + its shear part)",
                            std::abs(M - ref.base_moment_Nm),
                            dM + ref_error * ref.base_moment_Nm + shear_M, "N m");
              gates.at_most(what +
                                ": clamp force vs planar reference (bound: last ladder "
                                "change + reference error + its shear part)",
                            std::abs(F - ref.base_force_N),
                            dF + ref_error * ref.base_force_N + shear_F, "N");
              // Against the closed form: the measured distance closed form - reference plus
              // the bound above.
              gates.at_most(what +
                                ": clamp moment vs closed form / M (bound: closed form - "
                                "reference + the bound above)",
                            rel(M, cf.base_moment_Nm),
                            small_slope_m + (dM + ref_error * ref.base_moment_Nm + shear_M) /
                                                cf.base_moment_Nm);
              gates.at_most(
                  what +
                      ": clamp force vs closed form / F (bound: closed form - "
                      "reference + the bound above)",
                  rel(F, cf.base_force_N),
                  small_slope_f + (dF + ref_error * ref.base_force_N + shear_F) / cf.base_force_N);
              // Touchdown: a solver's point force at a contact point stands for the pressure
              // over its cell (half a spacing each side), and the touchdown is resolved to a
              // cell (first order): the first loaded point lies within 1.5 spacings of l.
              const double h = m.length_m / lad.levels.back();
              gates.at_most(what +
                                ": touchdown (first contact s0) vs planar reference l "
                                "(bound: 1.5 grid spacings L / level)",
                            std::abs(c.first_s_m - ref.free_span_m), 1.5 * h, "m");
            } else {
              gates.check(what + ": comparison with the references", false,
                          "no usable finest solve: " +
                              (finest.ok ? std::string("base_reaction missing (or on the "
                                                       "level before)")
                                         : finest.message),
                          "a converged solve with base_reaction");
            }
            std::string orders;
            for (std::size_t k = 1; k < changes_m.size(); ++k)
              orders += fmt::format("{}{:.2f}", k > 1 ? ", " : "",
                                    order_of(changes_m[k - 1], changes_m[k]));
            gates.check(what + ": observed order of the clamp moment (reported)", true,
                        orders.empty() ? "fewer than three levels" : orders, "not gated");
            // Shape of the finest solve (for the plot).
            for (std::size_t i = 0; i < finest.result.centerline_s_m.size(); ++i) {
              const Vector3d& p = finest.result.centerline_p_W_m[i];
              fmt::print(shape, "{},{},{},{:.8e},{:.10e},{:.10e}\n", H, lad.method,
                         lad.levels.back(), finest.result.centerline_s_m[i], p.x(), p.z());
            }
          }
        }
        // The closed form approaches the reference as the slope falls.
        for (std::size_t k = 1; k < gaps.size(); ++k) {
          gates.check(fmt::format("heavy rod: closed form vs elastica (small-slope error), "
                                  "clamp force, falls from H = {:.4g} to {:.4g} m",
                                  gaps[k - 1], gaps[k]),
                      closed_error_force[k] < closed_error_force[k - 1],
                      fmt::format("{:.3e} -> {:.3e} (slope {:.3e} -> {:.3e}; order in slope "
                                  "{:.2f})",
                                  closed_error_force[k - 1], closed_error_force[k], slopes[k - 1],
                                  slopes[k],
                                  std::log(closed_error_force[k - 1] / closed_error_force[k]) /
                                      std::log(slopes[k - 1] / slopes[k])),
                      "decreasing (O(slope^2) expected)");
        }
      }
      csv.commit();
      small.commit();
      shape.commit();
      params.commit();
    }

    // --------------------------------------------------------------------------------------
    fmt::print("Step 2: propped cantilever on a sphere\n");
    {
      tcasim::rod::AtomicOutput csv(out_dir + "/propped.csv", "propped csv");
      csv << "method,level,converged,reaction_N,closed_reaction_N,error_rel,change_N,"
             "model_bound_rel,time_s,message\n";
      const auto it = models.find("propped-cantilever-sphere");
      if (it == models.end()) {
        gates.not_run("step 2 propped cantilever", "propped-cantilever-sphere.json was not read");
      } else {
        const rod::RodModel& m = it->second;
        const rod::Obstacle& sphere = m.obstacles.at(0);
        const double r = 0.5 * m.section.properties_at(0.0).width_m;
        const double B = m.stiffness_at(0.0).bending_torsion.x();
        const double L = m.length_m;
        const double a = (sphere.point_W_m - m.base_position_W_m).dot(m.R_WB0.col(2));
        const double P = m.tip_force_W_N.norm();
        const double R = rod::propped_cantilever_reaction_N(P, L, a);
        // Model error of the closed form: (1) the contact point travels over the sphere by
        // (R_s + r) sin(theta_a), theta_a the rod's slope at a (small-slope solution:
        // (-P a (2 L - a) + R a^2) / (2 B)), which moves a and so R by dR/da = -3 P L / (2 a^2);
        // (2) the geometric nonlinearity, led by the curvature's 3/2 theta^2 (kappa = w'' (1 +
        // w'^2)^(-3/2)), theta the tip slope of the free cantilever P L^2 / (2 B) (an upper
        // bound of the propped rod's); (3) the rod's shear, which the closed form leaves out:
        // with the shear compliance 1 / (G A) the two deflections at a add P a / (G A) and
        // R a / (G A), so R_shear = P (a^2 (3 L - a) / (6 B) + a / GA) / (a^3 / (3 B) + a / GA)
        // (no shear factor, as the rod law), whose distance to R is computed, not assumed.
        const double GA = m.stiffness_at(0.0).shear_extension.x();
        const double R_shear =
            P * (a * a * (3 * L - a) / (6 * B) + a / GA) / (a * a * a / (3 * B) + a / GA);
        const double shear = rel(R_shear, R);
        const double theta_a = std::abs((-P * a * (2 * L - a) + R * a * a) / (2 * B));
        const double travel = (sphere.radius_m + r) * theta_a;
        const double theta_tip = P * L * L / (2 * B);
        const double model_bound =
            3.0 * P * L / (2 * a * a) * travel / R + 1.5 * theta_tip * theta_tip + shear;
        fmt::print(
            "  a = {:.4f} m, P = {:.4g} N: closed-form reaction {:.6e} N; model bound "
            "{:.2e} relative (travel {:.2e} m, tip slope {:.2e}, shear {:.2e})\n",
            a, P, R, model_bound, travel, theta_tip, shear);
        for (const Ladder& lad : all_ladders) {
          std::vector<double> reactions;
          std::string why;
          for (int level : lad.levels) {
            progress(fmt::format("propped cantilever, {}", level_label(lad, level)));
            const Outcome o = solve_once(m, lad.options(level), rod::Loads::from_model(m));
            const ContactTotal c = contact_total(m, o.result);
            const double reaction =
                o.ok && c.reported ? c.force_W_N.dot(-m.tip_force_W_N.normalized()) : kNaN;
            const double change = reactions.empty() ? kNaN : std::abs(reaction - reactions.back());
            reactions.push_back(reaction);
            if (!o.ok && why.empty()) why = o.message;
            if (o.ok && !c.reported && why.empty()) why = "no contacts in the result";
            fmt::print(csv, "{},{},{},{:.10e},{:.10e},{:.6e},{:.6e},{:.6e},{:.3f},\"{}\"\n",
                       lad.method, level, o.ok ? 1 : 0, reaction, R, rel(reaction, R), change,
                       model_bound, o.time_s, o.message);
          }
          const std::string what = "propped cantilever / " + lad.method;
          const double fin = reactions.back();
          const double change =
              reactions.size() >= 2 ? std::abs(fin - reactions[reactions.size() - 2]) : kNaN;
          gates.check(what + ": every solve converges with contacts", why.empty(),
                      why.empty() ? "ok" : why, "all");
          gates.at_most(what +
                            ": sphere reaction vs P (3 L - a) / (2 a), relative (bound: "
                            "contact-point travel + 3/2 slope^2 + last change)",
                        rel(fin, R), model_bound + change / R);
        }
      }
      csv.commit();
    }

    // --------------------------------------------------------------------------------------
    fmt::print("Step 3: global balance (base reaction + weight + tip loads + contacts = 0)\n");
    {
      tcasim::rod::AtomicOutput csv(out_dir + "/balance.csv", "balance csv");
      csv << "scenario,method,level,converged,has_base_reaction,contacts_reported,"
             "force_imbalance_N,force_bound_N,moment_imbalance_Nm,moment_bound_Nm,"
             "weight_moment_quadrature_Nm,residual,message\n";
      std::vector<std::pair<std::string, rod::RodModel>> cases;
      for (const auto& [name, m] : models) cases.emplace_back(name, m);
      // Two without obstacles: the base reaction alone balances the loads.
      if (models.count("heavy-rod-floor")) {
        rod::RodModel free = models.at("heavy-rod-floor");
        free.obstacles.clear();
        free.name = "heavy-rod-no-floor";
        cases.emplace_back(free.name, free);
      }
      try {
        cases.emplace_back(
            "three-tca-3d (no obstacles)",
            rod::read_scenario(std::string(TCASIM_SCENARIO_DIR) + "/three-tca-3d.json"));
      } catch (const std::exception& e) {
        gates.not_run("three-tca-3d balance", e.what());
      }
      const std::vector<Ladder> coarse = {{"cosserat", {quick ? 100 : 400}},
                                          {"fe", {quick ? 16 : 64}}};
      for (const auto& [name, m] : cases) {
        for (const Ladder& lad : coarse) {
          const int level = lad.levels.front();
          progress(fmt::format("{}: {}", name, level_label(lad, level)));
          const rod::Loads loads = rod::Loads::from_model(m);
          const Outcome o = solve_once(m, lad.options(level), loads);
          const Balance b =
              balance(m, loads, o.result,
                      lad.method == "cosserat" ? tcasim::cosserat::Options().tolerance : 0.0);
          const ContactTotal c = contact_total(m, o.result);
          fmt::print(
              csv, "\"{}\",{},{},{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.3e},\"{}\"\n", name,
              lad.method, level, o.ok ? 1 : 0, b.has_base_reaction ? 1 : 0, c.reported ? 1 : 0,
              b.force_N.norm(), b.force_bound_N, b.moment_Nm.norm(), b.moment_bound_Nm,
              b.weight_moment_quadrature_Nm, o.result.residual.value_or(kNaN), o.message);
          const std::string what = fmt::format("balance {} / {}", name, level_label(lad, level));
          if (!o.ok) {
            gates.check(what, false, "solve failed: " + o.message, "a converged solve");
            continue;
          }
          if (!b.has_base_reaction) {
            gates.check(what, false, "base_reaction missing from the result",
                        "base_reaction reported");
            continue;
          }
          if (!m.obstacles.empty() && !c.reported) {
            gates.check(what, false, "contacts missing from the result",
                        "one contacts entry per obstacle");
            continue;
          }
          gates.at_most(what +
                            ": force imbalance (bound: (nodes x residual + stopping tolerance) "
                            "x F_c + round-off)",
                        b.force_N.norm(), b.force_bound_N, "N");
          gates.at_most(what +
                            ": moment imbalance about the base (bound: as the force x L + "
                            "weight-moment quadrature)",
                        b.moment_Nm.norm(), b.moment_bound_Nm, "N m");
        }
      }
      csv.commit();
    }

    // --------------------------------------------------------------------------------------
    fmt::print("Step 4: cross-method agreement on the contact suite\n");
    {
      tcasim::rod::AtomicOutput csv(out_dir + "/contact_crosscheck.csv", "crosscheck csv");
      csv << "scenario,method,level,converged,tip_x_m,tip_y_m,tip_z_m,contact_force_x_N,"
             "contact_force_y_N,contact_force_z_N,regions,max_penetration_m,time_s,message\n";
      tcasim::rod::AtomicOutput sum(out_dir + "/contact_crosscheck_summary.csv", "summary csv");
      sum << "scenario,tip_difference_m,tip_bound_m,tip_difference_over_L,force_difference_N,"
             "force_bound_N,status\n";
      const std::vector<std::string> names =
          quick ? std::vector<std::string>{"heavy-rod-floor", "propped-cantilever-sphere",
                                           "three-tca-sphere"}
                : suite;
      for (const std::string& name : names) {
        if (!models.count(name)) continue;
        const rod::RodModel& m = models.at(name);
        struct Finest {
          Vector3d tip, force;
          double tip_change = kNaN, force_change = kNaN;
          double penetration_coarsest = kNaN, penetration_finest = kNaN;
          double residual_force_N = kNaN;  ///< finest level: residual x F_c
          double samples = 0.0;            ///< finest level: centerline samples
          bool ok = false;
          std::string why;
        };
        std::map<std::string, Finest> fin;
        for (const Ladder& lad : all_ladders) {
          Finest f;
          Vector3d prev_tip = Vector3d::Constant(kNaN), prev_force = Vector3d::Constant(kNaN);
          bool all_ok = true;
          for (int level : lad.levels) {
            progress(fmt::format("{}: {}", name, level_label(lad, level)));
            const Outcome o = solve_once(m, lad.options(level), rod::Loads::from_model(m));
            const ContactTotal c = contact_total(m, o.result);
            std::size_t regions = 0;
            for (const auto& ct : o.result.contacts) regions += ct.regions.size();
            fmt::print(csv, "{},{},{},{},{},{},{},{:.6e},{:.3f},\"{}\"\n", name, lad.method, level,
                       o.ok ? 1 : 0, fmt_vec(o.result.tip_position_W_m), fmt_vec(c.force_W_N),
                       regions, c.max_penetration_m, o.time_s, o.message);
            if (!o.ok || !c.reported) {
              all_ok = false;
              if (f.why.empty()) f.why = o.ok ? "no contacts in the result" : o.message;
            }
            f.tip_change = (o.result.tip_position_W_m - prev_tip).norm();
            f.force_change = (c.force_W_N - prev_force).norm();
            prev_tip = f.tip = o.result.tip_position_W_m;
            prev_force = f.force = c.force_W_N;
            if (std::isnan(f.penetration_coarsest)) f.penetration_coarsest = c.max_penetration_m;
            f.residual_force_N = o.result.residual.value_or(kNaN) * o.result.characteristic_force_N;
            f.samples = static_cast<double>(o.result.centerline_s_m.size());
            f.penetration_finest = c.max_penetration_m;
          }
          f.ok = all_ok;
          fin[lad.method] = f;
        }
        const Finest& a = fin["cosserat"];
        const Finest& b = fin["fe"];
        const std::string what = name + ": shooting vs FE (finest)";
        if (!a.ok || !b.ok) {
          const std::string why = !a.ok ? "shooting: " + a.why : "fe: " + b.why;
          gates.check(what, false, why, "converged solves with contacts");
          fmt::print(sum, "{},,,,,,\"{}\"\n", name, why);
          continue;
        }
        // Each finest level is within its last change of the limit: the two limits agree,
        // so the finest solves differ by at most the sum of the two changes, plus what each
        // solver's stopping test leaves: a residual force r F_c moves the tip by at most
        // r F_c L^3 / (3 B_min) (the clamped rod's largest compliance, a force at the tip on
        // its most compliant section), and the contact resultant by at most r F_c at each
        // of its nodes (as in the balance).
        double B_min = std::numeric_limits<double>::infinity();
        for (int k = 0; k <= 200; ++k) {
          const Vector3d K = m.bending_torsion_stiffness(
              m.length_m * k / 200.0, k == 200 ? rod::Side::kLeft : rod::Side::kRight);
          B_min = std::min({B_min, K.x(), K.y()});
        }
        const double L3 = m.length_m * m.length_m * m.length_m;
        const double tip_diff = (a.tip - b.tip).norm();
        const double tip_bound = a.tip_change + b.tip_change +
                                 (a.residual_force_N + b.residual_force_N) * L3 / (3.0 * B_min);
        const double force_diff = (a.force - b.force).norm();
        const double force_bound = a.force_change + b.force_change +
                                   a.residual_force_N * a.samples + b.residual_force_N * b.samples;
        fmt::print(sum, "{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},ok\n", name, tip_diff, tip_bound,
                   tip_diff / m.length_m, force_diff, force_bound);
        gates.at_most(what +
                          ": tip position difference (bound: sum of the last ladder changes + "
                          "residual compliance)",
                      tip_diff, tip_bound, "m");
        gates.at_most(what +
                          ": contact resultant difference (bound: sum of the last changes + "
                          "nodes x residual)",
                      force_diff, force_bound, "N");
        // No penalty: a penetration the solver leaves must vanish under refinement, so the
        // finest level's may not exceed the coarsest's, plus what the solver's convergence
        // test allows at its contact points: the shooting closes active gaps to `tolerance`
        // L, the FE solves them as equations (round-off of positions of size L, 1e3 eps L).
        for (const auto& [label, f] : fin) {
          const double allowed = label == "cosserat"
                                     ? tcasim::cosserat::Options().tolerance * m.length_m
                                     : 1e3 * kEps * m.length_m;
          gates.at_most(fmt::format("{}: {} max penetration, finest level (bound: the coarsest "
                                    "level's, {:.3e} m, + the solver's gap tolerance {:.1e} m)",
                                    name, label, f.penetration_coarsest, allowed),
                        f.penetration_finest, f.penetration_coarsest + allowed, "m");
        }
      }
      csv.commit();
      sum.commit();
    }

    // --------------------------------------------------------------------------------------
    fmt::print("Step 5: sweeps across contact onset (warm starts)\n");
    {
      tcasim::rod::AtomicOutput csv(out_dir + "/onset_sweep.csv", "onset sweep csv");
      csv << "case,points,method,load_kind,load,tip_x_m,tip_y_m,tip_z_m,contact_force_N,in_contact,"
             "closed_contact_force_N,closed_tip_deflection_m,onset,converged,message\n";
      // (a) A cantilever tangent to a cylinder at its clamp, tip force rising toward it: the
      // propped cantilever's rod with the sphere replaced.
      struct SweepCase {
        std::string name;
        rod::RodModel model;
        bool tip_force;  ///< true: scale the tip force; false: the TCA temperatures
        double onset;    ///< closed-form onset (cantilever on a cylinder) or NaN
        double B = 0.0, R = 0.0;
        double max_load_N = 0.0;  ///< tip force at the sweep's end
      };
      std::vector<SweepCase> sweeps;
      if (models.count("propped-cantilever-sphere")) {
        rod::RodModel m = models.at("propped-cantilever-sphere");
        const double r = 0.5 * m.section.properties_at(0.0).width_m;
        const double Rc = 10.0 * m.length_m;  // L << R: slopes below L / R on the cylinder
        rod::Obstacle cyl;
        cyl.name = "cylinder";
        cyl.type = rod::Obstacle::Type::kCylinder;
        cyl.direction_W = m.R_WB0.col(2).cross(-m.tip_force_W_N.normalized()).normalized();
        cyl.point_W_m = m.base_position_W_m + (r + Rc) * m.tip_force_W_N.normalized();
        cyl.radius_m = Rc;
        m.obstacles = {cyl};
        m.name = "cantilever-on-cylinder";
        const double B = m.stiffness_at(0.0).bending_torsion.x();
        const double onset = B / (Rc * m.length_m);
        sweeps.push_back({m.name, m, true, onset, B, Rc, 4.0 * onset});  // 0 .. 4 x the onset
      }
      if (models.count("rectangle-plane-corner")) {
        // Corner first, then the face, as the file's tip force is reached.
        const rod::RodModel& m = models.at("rectangle-plane-corner");
        sweeps.push_back({m.name, m, true, kNaN, 0.0, 0.0, m.tip_force_W_N.norm()});
      }
      if (models.count("tca-finger-cylinder")) {
        sweeps.push_back({"tca-finger-cylinder", models.at("tca-finger-cylinder"), false, kNaN});
      }
      for (const SweepCase& sc : sweeps) {
        for (const Ladder& lad :
             {Ladder{"cosserat", {quick ? 100 : 400}}, Ladder{"fe", {quick ? 16 : 64}}}) {
          double max_jump[2] = {kNaN, kNaN};
          for (int refine = 0; refine < 2; ++refine) {
            const int points = (quick ? 6 : 16) * (refine + 1) + 1;
            method::StaticSolver solver(sc.model, lad.options(lad.levels.front()));
            const rod::Loads base_loads = rod::Loads::from_model(sc.model);
            double prev_force = kNaN, jump = 0.0;
            bool in_contact_seen = false, zero_before = true, stays = true, all_ok = true;
            std::string why;
            const Vector3d dir = sc.tip_force ? sc.model.tip_force_W_N.normalized() : Vector3d();
            for (int k = 0; k < points; ++k) {
              const double t = static_cast<double>(k) / (points - 1);
              rod::Loads loads = base_loads;
              double load = 0.0;
              double closed_force = kNaN, closed_tip = kNaN;
              if (sc.tip_force) {
                load = sc.max_load_N * t;
                loads.tip_force_W_N = load * dir;
                if (!std::isnan(sc.onset)) {
                  const rod::CantileverOnCylinder cf =
                      rod::cantilever_on_cylinder(sc.B, sc.model.length_m, sc.R, load);
                  closed_force = cf.contact_force_N;
                  closed_tip = cf.tip_deflection_m;
                }
              } else {
                // Heat every TCA from the material's reference temperature to the file's.
                for (std::size_t i = 0; i < sc.model.actuators.size(); ++i) {
                  const auto& act = sc.model.actuators[i];
                  if (act.drive.type != rod::Drive::Type::kTca) continue;
                  const double ref_K = act.drive.tca->material().reference_temperature_K;
                  const double target_K = act.drive.segments.front().temperature_K;
                  loads.set_temperature_K(i, ref_K + t * (target_K - ref_K));
                  load = ref_K + t * (target_K - ref_K) - 273.15;
                }
              }
              const Outcome o = solve_safely(solver, loads);
              const ContactTotal c = contact_total(sc.model, o.result);
              const double force = c.force_W_N.norm();
              if (!o.ok || !c.reported) {
                all_ok = false;
                if (why.empty()) why = o.ok ? "no contacts in the result" : o.message;
              }
              if (o.ok && c.reported) {
                if (c.touching) in_contact_seen = true;
                if (!c.touching && in_contact_seen) stays = false;
                if (sc.tip_force && load < sc.onset && force != 0.0) zero_before = false;
                // Continuity after onset: increments between two points both in contact (at
                // the onset itself the resultant may jump: on the cylinder tangent at the
                // clamp the lift-off starts at the clamp, so the force F moves from the clamp
                // to the cylinder at once).
                if (!std::isnan(prev_force) && c.touching)
                  jump = std::max(jump, std::abs(force - prev_force));
                prev_force = c.touching ? force : kNaN;
              }
              const Vector3d& tip = o.result.tip_position_W_m;
              fmt::print(csv,
                         "{},{},{},{},{:.8e},{:.10e},{:.10e},{:.10e},{:.10e},{},{:.10e},"
                         "{:.10e},{:.10e},{},\"{}\"\n",
                         sc.name, points, lad.method,
                         sc.tip_force ? "tip_force_N" : "temperature_degC", load, tip.x(), tip.y(),
                         tip.z(), force, c.touching ? 1 : 0, closed_force, closed_tip, sc.onset,
                         o.ok ? 1 : 0, o.message);
            }
            max_jump[refine] = jump;
            const std::string what =
                fmt::format("onset sweep {} / {} ({} points)", sc.name, lad.method, points);
            if (!all_ok) {
              gates.check(what, false, why, "converged solves with contacts");
              max_jump[refine] = kNaN;
              continue;
            }
            gates.check(what + ": the obstacle is reached and kept", in_contact_seen && stays,
                        fmt::format("reached {}, kept {}", in_contact_seen, stays), "both");
            if (!std::isnan(sc.onset)) {
              gates.check(what + ": no contact force below the closed-form onset B / (R L)",
                          zero_before, zero_before ? "zero" : "non-zero", "exactly zero");
            }
          }
          if (!(max_jump[0] > 0.0)) {
            gates.check(fmt::format("onset sweep {} / {}: continuity", sc.name, lad.method), false,
                        "fewer than two points in contact in the coarser sweep",
                        "two or more (the ratio needs an increment after onset)");
            continue;
          }
          gates.at_most(fmt::format("onset sweep {} / {}: largest contact-force increment after "
                                    "onset, half step / full step (continuity)",
                                    sc.name, lad.method),
                        max_jump[1] / max_jump[0], kContinuityRatio);
        }
      }
      csv.commit();
    }

    gates.write_csv(out_dir);
    fmt::print("Wrote {}/*.csv and gates.csv ({:.1f} s)\n", out_dir, elapsed());
    return gates.finish();
  } catch (const std::exception& e) {
    fmt::print(stderr, "validate_contact: error: {}\n", e.what());
    return 2;
  }
}
