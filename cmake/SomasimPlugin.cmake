# somasim_add_plugin(NAME SOURCES ... [LIBS ...])
# Builds a plugin shared library named somasim_<NAME> into the plugin directory
# of the build tree (and installs it into the plugin directory of the package), warnings on.
include(${CMAKE_CURRENT_LIST_DIR}/SomasimWarnings.cmake)
function(somasim_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  set(target somasim_plugin_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE somasim::framework ${ARG_LIBS})
  somasim_enable_warnings(${target})
  if(COMMAND somasim_use_precompiled_headers)
    somasim_use_precompiled_headers(${target} plugin)
  endif()
  # Unresolved symbols are link errors, not load-time surprises. (Not in sanitizer builds: there
  # the sanitizer runtimes live in the executable, and a plugin resolves them when loaded.)
  if(NOT SOMASIM_SANITIZE AND NOT SOMASIM_FUZZ)
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    OUTPUT_NAME somasim_${name}
    LIBRARY_OUTPUT_DIRECTORY ${SOMASIM_PLUGIN_BUILD_DIR}
    CXX_VISIBILITY_PRESET hidden
    INSTALL_RPATH "$ORIGIN/../..")
  set_property(GLOBAL APPEND PROPERTY SOMASIM_PLUGIN_TARGETS ${target})
  install(TARGETS ${target} LIBRARY DESTINATION ${SOMASIM_PLUGIN_INSTALL_DIR})
  # The index file lets somasim find the library's plugins without loading it (plugin_index.hpp).
  if(SOMASIM_INDEX_COMMAND)
    add_custom_command(TARGET ${target} POST_BUILD
      COMMAND ${SOMASIM_INDEX_COMMAND} plugins index $<TARGET_FILE:${target}>
      COMMENT "Indexing plugin library ${name}" VERBATIM)
    if(TARGET somasim)
      add_dependencies(${target} somasim)
    endif()
    install(FILES $<TARGET_FILE:${target}>.index DESTINATION ${SOMASIM_PLUGIN_INSTALL_DIR})
  endif()
endfunction()
