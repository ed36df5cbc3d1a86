#pragma once
/// Where the shipped data (materials/, scenarios/) is found at run time.
#include <filesystem>
#include <string>
#include <vector>

namespace tcasim {

/// Folder of the program or shared library whose code holds `address` (a function of it),
/// empty when it cannot be told: the folder that installed data and plugins are found
/// relative to.
std::filesystem::path module_folder(const void* address);

/// The installed-tree folders of a search, in order, duplicates dropped: <module>/bin_relative
/// and <module>/lib_relative (module: module_folder(address), skipped when unknown), then
/// `install_dir` and `build_dir`. The search for the data (below) and for plugins
/// (beam_fe/umfpack_loader) each put their environment override in front.
std::vector<std::string> installed_folder_candidates(const void* address,
                                                     const std::string& bin_relative,
                                                     const std::string& lib_relative,
                                                     const std::string& install_dir,
                                                     const std::string& build_dir);

/// The folders data_directory() considers, in order:
///  1. the environment variable TCASIM_DATA_DIR, when set and non-empty (taken as given);
///  2. the installed package's data folder relative to the program or shared library that
///     holds this code: <its folder>/../share/tcasim for a program in <prefix>/bin or a
///     library in <prefix>/lib (the relative paths the build was configured with), so an
///     installed tree works wherever it is copied;
///  3. the data folder of the install prefix the build was configured with
///     (<CMAKE_INSTALL_PREFIX>/share/tcasim);
///  4. the source tree's data/ (a program run from the build tree).
std::vector<std::string> data_directory_candidates();

/// Folder holding the shipped data: TCASIM_DATA_DIR when set and non-empty, else the first
/// of the other candidates (data_directory_candidates) that holds a materials/ folder, else
/// the source tree's data/ (whose absence the caller then reports with the file it missed).
std::string data_directory();

}  // namespace tcasim
