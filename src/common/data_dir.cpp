#include "common/data_dir.hpp"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#if !defined(TCASIM_BUILD_DATA_DIR) || !defined(TCASIM_INSTALL_DATA_DIR) || \
    !defined(TCASIM_BINDIR_TO_DATA_DIR) || !defined(TCASIM_LIBDIR_TO_DATA_DIR)
#error "the data folders must be defined by the build (src/common/CMakeLists.txt)"
#endif

namespace tcasim {

// The dynamic loader names a shared library (link_map::l_name); the main program it leaves
// unnamed (dladdr would give argv[0], which need not be a path), and /proc/self/exe names it.
std::filesystem::path module_folder(const void* address) {
  Dl_info info{};
  link_map* map = nullptr;
  std::string module;
  if (dladdr1(address, &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) != 0 &&
      map != nullptr && map->l_name != nullptr) {
    module = map->l_name;
  }
  std::error_code ec;
  const std::filesystem::path path = module.empty()
                                         ? std::filesystem::read_symlink("/proc/self/exe", ec)
                                         : std::filesystem::canonical(module, ec);
  return ec ? std::filesystem::path() : path.parent_path();
}

std::vector<std::string> installed_folder_candidates(const void* address,
                                                     const std::string& bin_relative,
                                                     const std::string& lib_relative,
                                                     const std::string& install_dir,
                                                     const std::string& build_dir) {
  std::vector<std::string> out;
  const auto add = [&out](const std::string& dir) {
    if (std::find(out.begin(), out.end(), dir) == out.end()) out.push_back(dir);
  };
  if (const std::filesystem::path own = module_folder(address); !own.empty()) {
    add((own / bin_relative).lexically_normal().string());
    add((own / lib_relative).lexically_normal().string());
  }
  add(install_dir);
  add(build_dir);
  return out;
}

std::vector<std::string> data_directory_candidates() {
  std::vector<std::string> out = installed_folder_candidates(
      reinterpret_cast<const void*>(&data_directory_candidates), TCASIM_BINDIR_TO_DATA_DIR,
      TCASIM_LIBDIR_TO_DATA_DIR, TCASIM_INSTALL_DATA_DIR, TCASIM_BUILD_DATA_DIR);
  if (const char* env = std::getenv("TCASIM_DATA_DIR"); env != nullptr && *env != '\0') {
    out.erase(std::remove(out.begin(), out.end(), std::string(env)), out.end());
    out.insert(out.begin(), env);
  }
  return out;
}

std::string data_directory() {
  if (const char* env = std::getenv("TCASIM_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  for (const std::string& dir : data_directory_candidates()) {
    std::error_code ec;
    if (std::filesystem::is_directory(std::filesystem::path(dir) / "materials", ec)) return dir;
  }
  return TCASIM_BUILD_DATA_DIR;
}

}  // namespace tcasim
