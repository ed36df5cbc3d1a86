# Runs one command and checks its exit code and its output (stdout + stderr):
#   cmake -DCOMMAND=<program|arg|arg...> -DEXIT=<code> -DREGEX=<regular expression> -P expect_exit.cmake
# Arguments are separated by '|' (CMake lists do not survive add_test's quoting).
string(REPLACE "|" ";" command "${COMMAND}")
execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${rc}" STREQUAL "${EXIT}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXIT}\nstdout: ${out}\nstderr: ${err}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}'\nstdout: ${out}\nstderr: ${err}")
endif()
