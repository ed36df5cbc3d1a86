# ctest `package_install_and_consume` (cmake -P): installs the build into a fresh prefix,
# configures and builds examples/solve_scenario against it (find_package(tcasim)), installs
# the example into the same prefix and runs it there: it must solve the shipped scenario
# and find the shipped materials in the installed data folder, not in the source tree.
# Before that, the installed include tree must be public API only (TcasimInstalledHeaders.cmake).
# The installed tcasim loads the installed UMFPACK plugin (PLUGIN: its path under the prefix).
# Inputs: BUILD_DIR, SOURCE_DIR, WORK_DIR, GENERATOR, CXX_COMPILER, BUILD_TYPE, PLUGIN; PYTHON and
# PYTHON_SITE (the interpreter and the package folder under the prefix; empty: no module built);
# READELF (optional: the installed files' run paths are checked with it).
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER BUILD_TYPE PLUGIN)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "TcasimPackageTest.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix "${WORK_DIR}/prefix")
set(example_build "${WORK_DIR}/example-build")
file(REMOVE_RECURSE "${WORK_DIR}")

run("installing the build" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(file include/tcasim/tcasim/tcasim.hpp lib/cmake/tcasim/tcasimConfig.cmake
             lib/cmake/tcasim/tcasimConfigVersion.cmake share/tcasim/materials bin/tcasim
             ${PLUGIN})
  if(NOT EXISTS "${prefix}/${file}")
    file(GLOB_RECURSE installed RELATIVE "${prefix}" "${prefix}/*")
    message(FATAL_ERROR "the install lacks ${file}; it holds:\n${installed}")
  endif()
endforeach()

# The installed headers are the public API only: no internal/ folder, and every #include
# resolves to an installed header, the standard library, Eigen, fmt or nlohmann-json, never to
# a private dependency such as <klu.h> or SUNDIALS (TcasimInstalledHeaders.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/TcasimInstalledHeaders.cmake)
tcasim_check_installed_headers("${prefix}/include/tcasim")

run("configuring the example" ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/solve_scenario"
    -B "${example_build}" -G "${GENERATOR}" -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} "-DCMAKE_PREFIX_PATH=${prefix}")
run("building the example" ${CMAKE_COMMAND} --build "${example_build}")
run("installing the example" ${CMAKE_COMMAND} --install "${example_build}" --prefix "${prefix}")

# Run from the prefix with TCASIM_DATA_DIR unset: the data must come from the install.
run("running the installed example" ${CMAKE_COMMAND} -E env --unset=TCASIM_DATA_DIR
    "${prefix}/bin/solve_scenario")
message("${run_output}")
file(REAL_PATH "${prefix}/share/tcasim" installed_data)
string(FIND "${run_output}" "data: ${installed_data}\n" at)
if(at LESS 0)
  message(FATAL_ERROR "the installed example did not use the installed data ${installed_data}")
endif()
if(NOT run_output MATCHES "scenario: circular-manipulator\n.*tip_m: [-+0-9.e]+ [-+0-9.e]+ [-+0-9.e]+\n")
  message(FATAL_ERROR "the installed example printed no tip of circular-manipulator")
endif()

# The installed program solves the same installed scenario.
run("running the installed tcasim" ${CMAKE_COMMAND} -E env --unset=TCASIM_DATA_DIR
    "${prefix}/bin/tcasim" solve "${prefix}/share/tcasim/scenarios/circular-manipulator.json")
if(NOT run_output MATCHES "\"converged\": true")
  message(FATAL_ERROR "the installed tcasim did not solve the installed scenario:\n${run_output}")
endif()

# No installed program, library, plugin or module looks for libraries in the current directory
# (READELF: readelf, when CMake found it).
if(READELF)
  include(${CMAKE_CURRENT_LIST_DIR}/TcasimRunPaths.cmake)
  file(GLOB_RECURSE installed_elf LIST_DIRECTORIES false "${prefix}/lib/*.so" "${prefix}/lib/*.so.*")
  tcasim_check_run_paths("${READELF}" "${prefix}/bin/tcasim" "${prefix}/bin/solve_scenario" ${installed_elf})
endif()

# `--linear-solver umfpack` loads the installed plugin (found relative to the installed
# program, ahead of the build tree's): the dynamic loader's log names the file it opened.
file(REAL_PATH "${prefix}/${PLUGIN}" installed_plugin)
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=TCASIM_DATA_DIR --unset=TCASIM_PLUGIN_DIR
                        LD_DEBUG=files "${prefix}/bin/tcasim" solve
                        "${prefix}/share/tcasim/scenarios/circular-manipulator.json" --method fe
                        --linear-solver umfpack
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE loader_log)
if(NOT rc EQUAL 0 OR NOT out MATCHES "\"converged\": true")
  message(FATAL_ERROR "the installed tcasim did not solve with UMFPACK (${rc}):\n${out}\n${loader_log}")
endif()
string(FIND "${loader_log}" "file=${installed_plugin} " at)
if(at LESS 0)
  message(FATAL_ERROR "the installed tcasim did not load the installed plugin ${installed_plugin}")
endif()

# The installed Python package (when built: PYTHON and PYTHON_SITE given), imported from a
# folder outside the build tree with only the install on its path: it must be the installed
# module, use the installed data and load the installed UMFPACK plugin.
if(DEFINED PYTHON AND NOT PYTHON STREQUAL "")
  set(site "${prefix}/${PYTHON_SITE}")
  if(NOT EXISTS "${site}/tcasim/__init__.py")
    message(FATAL_ERROR "the install lacks the Python package ${site}/tcasim")
  endif()
  set(script [=[
import os, sys
import tcasim
print("module:", os.path.realpath(tcasim.__file__))
print("data:", os.path.realpath(tcasim.data_directory()))
sc = tcasim.load_scenario(sys.argv[1])
r = tcasim.solve(sc)
print("cosserat converged:", r.converged, "tip_m:", *r.tip_position_m)
fe = tcasim.solve(sc, method="fe", linear_solver="umfpack")
print("fe umfpack converged:", fe.converged)
]=])
  file(WRITE "${WORK_DIR}/import_installed.py" "${script}")
  execute_process(COMMAND ${CMAKE_COMMAND} -E chdir "${WORK_DIR}"
                          ${CMAKE_COMMAND} -E env --unset=TCASIM_DATA_DIR --unset=TCASIM_PLUGIN_DIR
                          "PYTHONPATH=${site}" LD_DEBUG=files ${PYTHON} "${WORK_DIR}/import_installed.py"
                          "${prefix}/share/tcasim/scenarios/circular-manipulator.json"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE py_output ERROR_VARIABLE py_loader_log)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the installed Python package failed (${rc}):\n${py_output}\n${py_loader_log}")
  endif()
  message("${py_output}")
  string(FIND "${py_loader_log}" "file=${installed_plugin} " at)
  if(at LESS 0)
    message(FATAL_ERROR "the installed Python package did not load the installed plugin ${installed_plugin}")
  endif()
  file(REAL_PATH "${site}/tcasim/__init__.py" installed_init)
  foreach(expected "module: ${installed_init}\n" "data: ${installed_data}\n"
                   "cosserat converged: True" "fe umfpack converged: True")
    string(FIND "${py_output}" "${expected}" at)
    if(at LESS 0)
      message(FATAL_ERROR "the installed Python package printed no '${expected}':\n${py_output}")
    endif()
  endforeach()
endif()
