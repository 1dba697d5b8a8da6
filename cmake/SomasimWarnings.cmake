# somasim_enable_warnings(TARGET): the warning set every somasim target builds with (and builds
# clean with under GCC): -Wall -Wextra -Wshadow -Wconversion (without -Wsign-conversion: the
# code indexes std::vector with int throughout, and clang's -Wconversion, which includes it, is
# turned down to the same set). With SOMASIM_WERROR (scripts/setup.sh, CI) warnings are errors.
# Installed with the package, so out-of-tree plugins get it too.
option(SOMASIM_WERROR "treat compiler warnings as errors" OFF)
function(somasim_enable_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wconversion)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    target_compile_options(${target} PRIVATE -Wno-sign-conversion)
  endif()
  if(SOMASIM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# somasim_enable_warnings_in(DIR): the same for every compiled target defined in DIR and its
# subdirectories (tests, benchmarks, tools), so that no target is left out.
function(somasim_enable_warnings_in dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    if(type MATCHES "EXECUTABLE|LIBRARY" AND NOT type STREQUAL "INTERFACE_LIBRARY")
      somasim_enable_warnings(${t})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    somasim_enable_warnings_in(${sub})
  endforeach()
endfunction()
