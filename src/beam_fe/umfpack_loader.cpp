// Finding and loading the UMFPACK plugin, as the shipped data is found (common/data_dir.hpp).
#include "beam_fe/internal/umfpack_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "beam_fe/beam_fe.hpp"
#include "common/blas_threads.hpp"
#include "common/data_dir.hpp"
#include "common/error.hpp"

#if !defined(TCASIM_UMFPACK_PLUGIN_FILE) || !defined(TCASIM_BUILD_PLUGIN_DIR) ||    \
    !defined(TCASIM_INSTALL_PLUGIN_DIR) || !defined(TCASIM_BINDIR_TO_PLUGIN_DIR) || \
    !defined(TCASIM_LIBDIR_TO_PLUGIN_DIR)
#error "the plugin folders must be defined by the build (src/beam_fe/CMakeLists.txt)"
#endif

namespace tcasim::beam_fe {

namespace {

/// Opens `path` and checks its factory and interface version: the plugin, or null with
/// `why` set.
const tcasim_umfpack_plugin* open_plugin(const std::string& path, std::string& why) {
  // RTLD_LOCAL: UMFPACK's and BLAS's symbols stay out of the program's global scope.
  void* const handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* const error = dlerror();
    why = error != nullptr ? error : path + ": dlopen failed";
    return nullptr;
  }
  const auto factory =
      reinterpret_cast<tcasim_umfpack_plugin_factory>(dlsym(handle, TCASIM_UMFPACK_PLUGIN_FACTORY));
  const tcasim_umfpack_plugin* const plugin = factory != nullptr ? factory() : nullptr;
  if (plugin == nullptr) {
    why = path + ": no " TCASIM_UMFPACK_PLUGIN_FACTORY " in it";
  } else if (plugin->abi_version != TCASIM_UMFPACK_PLUGIN_ABI) {
    why = fmt::format("{}: plugin interface version {}, this build needs {}", path,
                      plugin->abi_version, TCASIM_UMFPACK_PLUGIN_ABI);
  } else {
    // OpenBLAS (a dependency of UMFPACK) started its spinning server threads during dlopen.
    limit_blas_threads_of(handle);
    return plugin;
  }
  dlclose(handle);
  return nullptr;
}

/// The first candidate that loads; InputError listing every attempt otherwise.
const tcasim_umfpack_plugin& load_plugin() {
  std::vector<std::string> tried;
  for (const std::string& dir : umfpack_plugin_candidates()) {
    const std::string path = (std::filesystem::path(dir) / TCASIM_UMFPACK_PLUGIN_FILE).string();
    std::string why;
    if (const tcasim_umfpack_plugin* plugin = open_plugin(path, why)) return *plugin;
    tried.push_back(std::move(why));
  }
  throw InputError("linear_solver", "umfpack",
                   fmt::format("needs the UMFPACK plugin " TCASIM_UMFPACK_PLUGIN_FILE
                               ", which could not be loaded ({}); TCASIM_PLUGIN_DIR names the "
                               "folder holding it",
                               fmt::join(tried, "; ")));
}

}  // namespace

std::vector<std::string> umfpack_plugin_candidates() {
  if (const char* env = std::getenv("TCASIM_PLUGIN_DIR"); env != nullptr && *env != '\0') {
    return {env};
  }
  return installed_folder_candidates(reinterpret_cast<const void*>(&umfpack_plugin_candidates),
                                     TCASIM_BINDIR_TO_PLUGIN_DIR, TCASIM_LIBDIR_TO_PLUGIN_DIR,
                                     TCASIM_INSTALL_PLUGIN_DIR, TCASIM_BUILD_PLUGIN_DIR);
}

const tcasim_umfpack_plugin& umfpack_plugin() {
  static std::mutex mutex;
  static const tcasim_umfpack_plugin* loaded = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (loaded == nullptr) loaded = &load_plugin();
  return *loaded;
}

void load_linear_solver(LinearSolver kind) {
  if (kind == LinearSolver::kUmfpack) (void)umfpack_plugin();
}

}  // namespace tcasim::beam_fe
