# tcasim_check_installed_headers(ROOT): the installed include tree ROOT (<prefix>/include/tcasim,
# the consumer's include directory) holds the public API only, or configuration stops with a
# FATAL_ERROR naming every offending file and #include line:
#   - no folder named `internal` (a component's private headers, src/<component>/internal/),
#     and no installed header names an internal/ path, not even in a comment;
#   - every #include of every installed header names a header installed under ROOT ("x" next
#     to the including header or under ROOT, <x> under ROOT), a C++ standard library header
#     (<vector>: no extension), Eigen (<Eigen/...>) or a public dependency of the libraries:
#     fmt (<fmt/...>) and nlohmann-json (<nlohmann/...>), which tcasimConfig.cmake finds.
# So a header that includes a private dependency (SuiteSparse: <klu.h>, <umfpack.h>; SUNDIALS:
# <cvode/...>, <sundials/...>, <nvector/...>, <sunlinsol/...>, <sunmatrix/...>), an internal/
# path or a header that is not installed fails. Used by TcasimPackageTest.cmake; on its own:
#   cmake -DROOT=<prefix>/include/tcasim -P cmake/TcasimInstalledHeaders.cmake
function(tcasim_check_installed_headers root)
  get_filename_component(root "${root}" ABSOLUTE)
  if(NOT IS_DIRECTORY "${root}")
    message(FATAL_ERROR "installed headers: ${root} is not a folder")
  endif()
  set(problems "")
  file(GLOB_RECURSE entries LIST_DIRECTORIES true RELATIVE "${root}" "${root}/*")
  foreach(entry IN LISTS entries)
    if(entry MATCHES "^internal(/|$)" OR entry MATCHES "/internal(/|$)")
      string(APPEND problems "  ${entry}: a private (internal/) header or folder is installed\n")
    endif()
  endforeach()
  file(GLOB_RECURSE headers LIST_DIRECTORIES false RELATIVE "${root}" "${root}/*")
  if(NOT headers)
    string(APPEND problems "  no header is installed\n")
  endif()
  set(private_dependency
      "^(klu|umfpack|cholmod|amd|colamd|camd|ccolamd|btf|SuiteSparse_config)\\.h$|^(cvode|cvodes|ida|idas|arkode|kinsol|sundials|nvector|sunlinsol|sunmatrix|sunnonlinsol|sunmemory|sunadaptcontroller)/")
  foreach(header IN LISTS headers)
    get_filename_component(folder "${root}/${header}" DIRECTORY)
    file(STRINGS "${root}/${header}" mentions REGEX "internal/")
    foreach(line IN LISTS mentions)
      string(STRIP "${line}" line)
      string(APPEND problems "  ${header}: `${line}` names an internal/ path\n")
    endforeach()
    file(STRINGS "${root}/${header}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS lines)
      if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*([<\"])([^>\"]+)[>\"]")
        string(APPEND problems "  ${header}: `${line}` names no header\n")
        continue()
      endif()
      set(quoted "${CMAKE_MATCH_1}")
      set(name "${CMAKE_MATCH_2}")
      if(name MATCHES "^internal/" OR name MATCHES "/internal/")
        string(APPEND problems "  ${header}: `${line}` includes a private (internal/) header\n")
      elseif(name MATCHES "${private_dependency}")
        string(APPEND problems "  ${header}: `${line}` includes a private dependency\n")
      elseif(quoted STREQUAL "\"" AND EXISTS "${folder}/${name}"
             AND NOT IS_DIRECTORY "${folder}/${name}")
        # next to the including header
      elseif(EXISTS "${root}/${name}" AND NOT IS_DIRECTORY "${root}/${name}")
        # an installed header
      elseif(quoted STREQUAL "<" AND name MATCHES "^[a-z_]+$")
        # the C++ standard library
      elseif(quoted STREQUAL "<" AND name MATCHES "^(Eigen|fmt|nlohmann)/")
        # Eigen and the public dependencies
      else()
        string(APPEND problems "  ${header}: `${line}` is neither an installed header, the standard "
                               "library, Eigen, fmt nor nlohmann-json\n")
      endif()
    endforeach()
  endforeach()
  if(problems)
    message(FATAL_ERROR "the installed include tree ${root} is not public API only:\n${problems}")
  endif()
  list(LENGTH headers count)
  message(STATUS "installed headers: ${count} under ${root}, public API only")
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT DEFINED ROOT)
    message(FATAL_ERROR "TcasimInstalledHeaders.cmake: -DROOT=<prefix>/include/tcasim is required")
  endif()
  tcasim_check_installed_headers("${ROOT}")
endif()
