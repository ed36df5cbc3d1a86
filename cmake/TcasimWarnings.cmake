# tcasim_target_warnings(target): warnings on our own targets only.
function(tcasim_target_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                           -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual
                           -Wdouble-promotion -Wformat=2)
  endif()
endfunction()
