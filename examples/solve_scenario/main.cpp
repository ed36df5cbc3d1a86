// Solves a scenario with the Cosserat shooting solver of an installed tcasim and prints
// the tip position. Usage: solve_scenario [scenario.json] (default: a shipped scenario).
#include <cstdio>
#include <exception>
#include <string>
#include <tcasim/tcasim.hpp>

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : DEFAULT_SCENARIO;
  try {
    const tcasim::rod::RodModel model = tcasim::rod::read_scenario(file);
    const tcasim::rod::Result result = tcasim::cosserat::solve(model, tcasim::cosserat::Options{});
    std::printf("scenario: %s\n", model.name.c_str());
    std::printf("data: %s\n", tcasim::data_directory().c_str());
    if (!result.converged) {
      std::printf("not converged: %s\n", result.message.c_str());
      return 1;
    }
    const auto& tip = result.tip_position_W_m;
    std::printf("tip_m: %.9e %.9e %.9e\n", tip.x(), tip.y(), tip.z());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solve_scenario: %s\n", e.what());
    return 2;
  }
}
