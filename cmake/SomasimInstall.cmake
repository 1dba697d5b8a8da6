# Package config so that out-of-tree plugins can do find_package(somasim) and
# somasim_add_plugin(...): from the install prefix (`cmake --install build --prefix P`) or from
# the build tree itself (CMAKE_PREFIX_PATH=build).
include(CMakePackageConfigHelpers)
set(SOMASIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/somasim)
install(EXPORT somasimTargets NAMESPACE somasim:: DESTINATION ${SOMASIM_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/somasimConfig.cmake.in
  ${CMAKE_BINARY_DIR}/package-install/somasimConfig.cmake INSTALL_DESTINATION ${SOMASIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/somasimConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package-install/somasimConfig.cmake
  ${CMAKE_BINARY_DIR}/somasimConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/somasimDependencies.cmake
  ${PROJECT_SOURCE_DIR}/cmake/SomasimPlugin.cmake
  ${PROJECT_SOURCE_DIR}/cmake/SomasimWarnings.cmake DESTINATION ${SOMASIM_CMAKE_DIR})
# The build tree as a package too.
export(EXPORT somasimTargets NAMESPACE somasim:: FILE ${CMAKE_BINARY_DIR}/somasimTargets.cmake)
configure_file(${PROJECT_SOURCE_DIR}/cmake/somasimBuildTreeConfig.cmake.in
  ${CMAKE_BINARY_DIR}/somasimConfig.cmake @ONLY)
