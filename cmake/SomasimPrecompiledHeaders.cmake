# Precompiled headers (SOMASIM_PRECOMPILE_HEADERS): the third-party headers nearly every
# translation unit parses (Eigen, nlohmann-json, spdlog, fmt, the standard library) are compiled
# once per kind of target — once for the core libraries, once for the plugins — and reused by
# every target of that kind. It shortens a cold build; the quick start turns it on. Off by
# default: clang-tidy cannot read GCC's precompiled headers, and incremental builds gain little.
option(SOMASIM_PRECOMPILE_HEADERS "Precompile the common third-party headers" OFF)

if(SOMASIM_PRECOMPILE_HEADERS)
  # GCC uses a precompiled header only where the macros the headers depend on are the same:
  # -pthread (_REENTRANT), which some dependencies add (Pango, MPI), everywhere; a translation
  # unit that still differs compiles without it (a warning, not an error).
  add_compile_options(-pthread -Wno-error=invalid-pch)
endif()

set(SOMASIM_PCH_HEADERS
  <algorithm> <cmath> <cstdint> <filesystem> <functional> <map> <memory> <optional> <string>
  <unordered_map> <utility> <vector>
  <Eigen/Core> <Eigen/Geometry> <nlohmann/json.hpp> <spdlog/spdlog.h> <fmt/format.h>)

# somasim_use_precompiled_headers(TARGET KIND): KIND is "library" (core shared libraries) or
# "plugin" (plugin modules). The headers are compiled once per kind, in a target that holds
# nothing else (somasim_pch_KIND: the kind's flags and the headers' dependencies only, so that no
# target's own macros leak into it), and every target of that kind reuses them.
function(somasim_use_precompiled_headers target kind)
  if(NOT SOMASIM_PRECOMPILE_HEADERS)
    return()
  endif()
  # One macro for every target of a kind (not CMake's <target>_EXPORTS, which differs per
  # target and would make GCC refuse the shared precompiled header).
  set_target_properties(${target} PROPERTIES DEFINE_SYMBOL SOMASIM_BUILDING_${kind})
  set(pch somasim_pch_${kind})
  if(NOT TARGET ${pch})
    set(source ${CMAKE_BINARY_DIR}/somasim_pch_${kind}.cpp)
    file(WRITE ${source} "// Holds the precompiled headers of somasim's ${kind} targets.\n")
    if(kind STREQUAL "plugin")
      add_library(${pch} MODULE ${source})
      set_target_properties(${pch} PROPERTIES CXX_VISIBILITY_PRESET hidden)
      target_link_libraries(${pch} PRIVATE somasim::framework)
    else()
      add_library(${pch} SHARED ${source})
      target_link_libraries(${pch} PRIVATE Eigen3::Eigen spdlog::spdlog fmt::fmt
                                           nlohmann_json::nlohmann_json)
    endif()
    target_compile_features(${pch} PRIVATE cxx_std_20)
    set_target_properties(${pch} PROPERTIES DEFINE_SYMBOL SOMASIM_BUILDING_${kind}
                                            LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/pch)
    somasim_enable_warnings(${pch})
    target_precompile_headers(${pch} PRIVATE ${SOMASIM_PCH_HEADERS})
    if(kind STREQUAL "plugin")
      # Every plugin includes the plugin interface (nearly 2 s of parsing per translation unit).
      target_precompile_headers(${pch} PRIVATE <somasim/plugin.hpp>)
    endif()
  endif()
  target_precompile_headers(${target} REUSE_FROM ${pch})
endfunction()
