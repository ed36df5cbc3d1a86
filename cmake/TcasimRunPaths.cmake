# The run paths (DT_RPATH, DT_RUNPATH) of ELF files must not name the current directory: an
# empty entry, or one that is neither absolute nor relative to the file ($ORIGIN), makes the
# dynamic loader look for the file's libraries in whatever directory it is started from.
#   include(TcasimRunPaths.cmake) and tcasim_check_run_paths(<readelf> <file>...), or
#   cmake -DREADELF=<readelf> "-DFILES=<file>|<file>..." -P TcasimRunPaths.cmake
# Fails (FATAL_ERROR) naming the file, its run path and the entry; prints every file's.
function(tcasim_check_run_paths readelf)
  foreach(file IN LISTS ARGN)
    if(NOT EXISTS "${file}")
      message(FATAL_ERROR "run paths: ${file} does not exist")
    endif()
    execute_process(COMMAND "${readelf}" -d "${file}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "run paths: ${readelf} -d ${file} failed (${rc}): ${err}")
    endif()
    string(REGEX MATCHALL "Library r[a-z]*path: \\[[^]\n]*\\]" paths "${out}")
    if(NOT paths)
      message(STATUS "run paths: ${file}: none")
    endif()
    foreach(line IN LISTS paths)
      string(REGEX REPLACE "^Library r[a-z]*path: \\[(.*)\\]$" "\\1" path "${line}")
      message(STATUS "run paths: ${file}: [${path}]")
      # Every entry, the empty ones included (a list of ":" would drop them).
      string(REPLACE ":" ";|" entries "|${path}")
      foreach(entry IN LISTS entries)
        string(REGEX REPLACE "^\\|" "" entry "${entry}")
        if(NOT entry MATCHES "^(/|\\$ORIGIN|\\$\\{ORIGIN\\})")
          message(FATAL_ERROR "run paths: ${file} has the run path [${path}] with the entry "
                              "'${entry}', which is neither absolute nor relative to $ORIGIN: "
                              "the loader would look for libraries in the current directory")
        endif()
      endforeach()
    endforeach()
  endforeach()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT READELF OR NOT FILES)
    message(FATAL_ERROR "TcasimRunPaths.cmake: -DREADELF=... and -DFILES=a|b|... are required")
  endif()
  string(REPLACE "|" ";" files "${FILES}")
  tcasim_check_run_paths("${READELF}" ${files})
endif()
