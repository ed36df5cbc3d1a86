// tcasim: command-line front end. See `tcasim --help`.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/cli_util.hpp"
#include "apps/commands.hpp"
#include "common/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"tcasim: kinetostatics of soft robots actuated by twisted-and-coiled actuators"};
  app.require_subcommand(1);
  tcasim::app::add_tca_command(app);
  tcasim::app::add_fit_command(app);
  tcasim::app::add_solve_command(app);
  tcasim::app::add_sweep_command(app);
  tcasim::app::add_inverse_command(app);
  tcasim::app::add_grasp_command(app);
  tcasim::app::add_compare_command(app);
  tcasim::app::add_converge_command(app);
  tcasim::app::add_simulate_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return app.exit(e);  // a subcommand's own exit code (e.g. 4: not converged)
  } catch (const CLI::ParseError& e) {
    // A malformed command line is an input error like a bad file (--help exits 0).
    const int code = app.exit(e);
    return code == 0 ? 0 : tcasim::app::kExitInputError;
  } catch (const tcasim::InputError& e) {
    fmt::print(stderr, "tcasim: input error: {}\n", e.what());
    return tcasim::app::kExitInputError;
  } catch (const tcasim::DomainError& e) {
    fmt::print(stderr, "tcasim: outside the model's domain: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "tcasim: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
