#include <utility>

#include "method/method.hpp"

namespace tcasim::method {

namespace {

/// The shooting method: ShootingSolver with its Solution carried between solves.
struct Shooting {
  cosserat::ShootingSolver solver;
  cosserat::Solution solution;
  Shooting(const rod::RodModel& model, const cosserat::Options& options) : solver(model, options) {}
  rod::Result solve(const rod::Loads& loads) {
    const cosserat::Summary summary = solver.solve(loads, solution);
    return solver.make_result(loads, solution, summary);
  }
  void reset() { solution = cosserat::Solution(); }
};

/// The beam FE: its Solver with the State carried between solves.
struct Fe {
  beam_fe::Solver solver;
  beam_fe::State state;
  Fe(const rod::RodModel& model, const beam_fe::Options& options) : solver(model, options) {}
  rod::Result solve(const rod::Loads& loads) {
    const beam_fe::Summary summary = solver.solve(loads, state);
    return solver.make_result(loads, state, summary);
  }
  void reset() { state = beam_fe::State(); }
};

}  // namespace

struct StaticSolver::Impl {
  std::variant<Shooting, Fe> solver;
};

const char* name(const StaticOptions& options) {
  return std::holds_alternative<cosserat::Options>(options) ? "cosserat" : "fe";
}

StaticSolver::StaticSolver(const rod::RodModel& model, const StaticOptions& options) {
  if (const auto* o = std::get_if<cosserat::Options>(&options)) {
    impl_.reset(new Impl{std::variant<Shooting, Fe>(std::in_place_type<Shooting>, model, *o)});
  } else {
    impl_.reset(new Impl{std::variant<Shooting, Fe>(std::in_place_type<Fe>, model,
                                                    std::get<beam_fe::Options>(options))});
  }
}

StaticSolver::~StaticSolver() = default;
StaticSolver::StaticSolver(StaticSolver&&) noexcept = default;
StaticSolver& StaticSolver::operator=(StaticSolver&&) noexcept = default;

rod::Result StaticSolver::solve(const rod::Loads& loads) {
  return std::visit([&](auto& s) { return s.solve(loads); }, impl_->solver);
}

void StaticSolver::reset() {
  std::visit([](auto& s) { s.reset(); }, impl_->solver);
}

const char* StaticSolver::method() const {
  return std::holds_alternative<Shooting>(impl_->solver) ? "cosserat" : "fe";
}

rod::Result solve(const rod::RodModel& model, const StaticOptions& options) {
  return StaticSolver(model, options).solve(rod::Loads::from_model(model));
}

}  // namespace tcasim::method
