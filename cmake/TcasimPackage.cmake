# The installable package: `cmake --install` puts the libraries, their headers, the shipped
# data and the `tcasim` program under the prefix, with a CMake package so a project can
#   find_package(tcasim 0.1 REQUIRED)
#   target_link_libraries(app PRIVATE tcasim::tcasim)        # or single components
# Components (exported names): tcasim::common, tca, rod, cosserat, beam_fe, crosscheck, study;
# tcasim::tcasim links them all. Layout:
#   <prefix>/include/tcasim/...            public headers (as under src/: "rod/scenario.hpp",
#                                          without the components' internal/ folders);
#                                          the umbrella header is <tcasim/tcasim.hpp>
#   <prefix>/lib/libtcasim_*.a             the libraries (.so with -DBUILD_SHARED_LIBS=ON; the
#                                          installed ones and the program find each other
#                                          through a relative RPATH, $ORIGIN)
#   <prefix>/lib/tcasim/libtcasim_umfpack.so  the beam FE's UMFPACK back end, a plugin loaded at
#                                          run time (beam_fe.hpp: umfpack_plugin_candidates)
#   <prefix>/lib/cmake/tcasim/             tcasimConfig.cmake, version file, targets
#   <prefix>/share/tcasim/materials/       shipped material laws (common/data_dir.hpp)
#   <prefix>/share/tcasim/scenarios/       shipped scenarios
#   <prefix>/bin/tcasim                    the command-line program
include(CMakePackageConfigHelpers)

set(TCASIM_COMPONENTS common tca rod cosserat beam_fe method crosscheck study)
set(TCASIM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/tcasim")

# The umbrella target: every component. Its target name differs from the `tcasim` program's.
add_library(tcasim_tcasim INTERFACE)
add_library(tcasim::tcasim ALIAS tcasim_tcasim)
set_target_properties(tcasim_tcasim PROPERTIES EXPORT_NAME tcasim)

# Run paths. A static build (the default) needs none and sets none. Shared libraries
# (BUILD_SHARED_LIBS) find each other in their own folder and the program finds them in the
# library folder, wherever the prefix is moved: $ORIGIN run paths. The build tree has the
# install's layout (bin/, <libdir>/ with the libraries, <libdir>/tcasim/ with the plugin), so
# it is built with those same run paths (BUILD_WITH_INSTALL_RPATH). Otherwise CMake would
# give the build tree's files their own run paths padded with empty entries, room for the
# install's to be written in on install, and an empty entry means the current directory: a
# library of that name wherever the program is started would be loaded. ctest
# run_paths_name_no_current_directory checks the build tree, the package test the install.
file(RELATIVE_PATH _tcasim_bin_to_lib "${CMAKE_INSTALL_FULL_BINDIR}" "${CMAKE_INSTALL_FULL_LIBDIR}")
set(TCASIM_BUILD_LIB_DIR "${PROJECT_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}")
set(_tcasim_targets tcasim_tcasim)
foreach(component IN LISTS TCASIM_COMPONENTS)
  set(target tcasim_${component})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${component})
  if(BUILD_SHARED_LIBS)
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN" BUILD_WITH_INSTALL_RPATH ON
                          LIBRARY_OUTPUT_DIRECTORY "${TCASIM_BUILD_LIB_DIR}")
  endif()
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_link_libraries(tcasim_tcasim INTERFACE tcasim::${component})
  list(APPEND _tcasim_targets ${target})
endforeach()

install(TARGETS ${_tcasim_targets} EXPORT tcasimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime
        INCLUDES DESTINATION ${TCASIM_INSTALL_INCLUDEDIR})
# The public headers only: a component's internal/ folder holds the headers its own sources
# and tests share (they may include private dependencies such as <klu.h>); the package test
# checks the installed include tree (TcasimPackageTest.cmake).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${TCASIM_INSTALL_INCLUDEDIR}
        COMPONENT development FILES_MATCHING PATTERN "*.hpp" PATTERN "internal" EXCLUDE)
install(EXPORT tcasimTargets NAMESPACE tcasim:: DESTINATION ${TCASIM_INSTALL_CMAKEDIR}
        COMPONENT development)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/tcasimConfig.cmake.in
  ${PROJECT_BINARY_DIR}/tcasimConfig.cmake
  INSTALL_DESTINATION ${TCASIM_INSTALL_CMAKEDIR}
  PATH_VARS TCASIM_INSTALL_DATADIR)
# 0.x: a minor version may break the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tcasimConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tcasimConfig.cmake ${PROJECT_BINARY_DIR}/tcasimConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/TcasimSuiteSparse.cmake
        DESTINATION ${TCASIM_INSTALL_CMAKEDIR} COMPONENT development)

# Shipped data, found at run time relative to the installed program or library.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${TCASIM_INSTALL_DATADIR} COMPONENT runtime)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/validation/scenarios/ DESTINATION ${TCASIM_INSTALL_DATADIR}/scenarios
        COMPONENT runtime)
# The program (build tree: bin/, as installed with the default CMAKE_INSTALL_BINDIR; with
# another one the build tree's program keeps CMake's own build run path).
if(BUILD_SHARED_LIBS)
  set_target_properties(tcasim PROPERTIES INSTALL_RPATH "$ORIGIN/${_tcasim_bin_to_lib}")
  get_target_property(_tcasim_bin tcasim RUNTIME_OUTPUT_DIRECTORY)
  file(RELATIVE_PATH _tcasim_build_bin_to_lib "${_tcasim_bin}" "${TCASIM_BUILD_LIB_DIR}")
  if(_tcasim_build_bin_to_lib STREQUAL _tcasim_bin_to_lib)
    set_target_properties(tcasim PROPERTIES BUILD_WITH_INSTALL_RPATH ON)
  endif()
  unset(_tcasim_bin)
  unset(_tcasim_build_bin_to_lib)
endif()
install(TARGETS tcasim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
unset(_tcasim_targets)
unset(_tcasim_bin_to_lib)
