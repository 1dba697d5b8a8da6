# somasim_add_library(NAME SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# Builds one library of core/: the shared library somasim_<NAME> (alias somasim::<NAME>) from
# the calling folder's sources, with that folder's include/ as its public headers, warnings on,
# and installs both (headers under include/somasim/<NAME>/ or, for the framework, include/somasim/).
function(somasim_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(target somasim_${name})
  add_library(${target} SHARED ${ARG_SOURCES})
  add_library(somasim::${name} ALIAS ${target})
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  somasim_enable_warnings(${target})
  somasim_use_precompiled_headers(${target} library)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  install(TARGETS ${target} EXPORT somasimTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/somasim
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
