#pragma once
/// Loading the UMFPACK plugin (umfpack_plugin_abi.hpp) for the solver; the public side is
/// in beam_fe.hpp (umfpack_plugin_candidates, load_linear_solver).
#include "beam_fe/internal/umfpack_plugin_abi.hpp"

namespace tcasim::beam_fe {

/// The loaded plugin's functions, loading it on the first call (thread-safe; a loaded plugin
/// stays for the life of the process, a failure is retried at the next call). InputError
/// `linear_solver = umfpack ...` naming every path tried and why it failed otherwise.
const tcasim_umfpack_plugin& umfpack_plugin();

}  // namespace tcasim::beam_fe
