#pragma once
/// Subcommands of the `tcasim` command line. Each add_* function registers one
/// subcommand on the application; its callback does the work and throws on error
/// (main turns every exception into a message and a non-zero exit code).
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdlib>
#include <string>

namespace tcasim::app {

/// A check on the text of an integer flag: CLI11 2.1 reads an integer beyond 64 bits as the
/// nearest bound without a word, so the flag's rule would report a number the user did not
/// give. Refused here instead (a parse error: exit code 2, naming the flag and the text).
inline CLI::Validator fits_64_bits() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        (void)std::strtoll(text.c_str(), &end, 0);
        if (errno != ERANGE) return {};
        return text + " must be an integer in [-9223372036854775808, 9223372036854775807]";
      },
      "");
}

/// `tcasim tca FILE.json [--tca ID] (--tension-N F | --load-g M) --temperatures-degC A:B:S`
void add_tca_command(CLI::App& app);
/// `tcasim fit ...`: calibration of TCA material parameters to measured curves.
void add_fit_command(CLI::App& app);

/// `tcasim solve SCENARIO [--method cosserat|fe] [--steps N | --rtol X] [--elements N --order 1|2]
/// [--out F]`
void add_solve_command(CLI::App& app);
/// `tcasim sweep SCENARIO --actuator NAME (--temperatures-degC A:B:S | --tensions-N A:B:S)
/// [--method cosserat|fe]`
void add_sweep_command(CLI::App& app);

/// `tcasim inverse SCENARIO --target-m X,Y,Z [--actuators a,b] [--max-temperature-degC T] [--out
/// F]`
void add_inverse_command(CLI::App& app);
/// `tcasim grasp SCENARIO --mass-g M --friction MU --fingers N [--max-temperature-degC T] [--out
/// F]`
void add_grasp_command(CLI::App& app);
/// `tcasim compare SCENARIO [--elements N,...] [--orders 1,2] [--out CSV]`: FE vs shooting table
void add_compare_command(CLI::App& app);
/// `tcasim converge SCENARIO --order 1|2 --levels K [--coarsest N] [--out CSV]`: FE error table
void add_converge_command(CLI::App& app);

/// `tcasim simulate SCENARIO --duration-s T --dt-s DT [--alpha A] [--output-every K] --out CSV
/// [--vtk-series DIR]`: rod dynamics, trajectory CSV
void add_simulate_command(CLI::App& app);

}  // namespace tcasim::app
