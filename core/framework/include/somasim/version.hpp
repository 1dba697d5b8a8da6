#pragma once
/// @file
/// Version strings of the somasim package and of its plugin interface.
#include <string>

namespace somasim {

/// Version of the somasim package (semantic versioning).
inline constexpr const char* kVersion = "0.1.0";

/// Version of the binary plugin interface. A plugin library records the string it was built
/// with; the loader rejects a library whose string differs. Bump it whenever a
/// public header that plugins include changes layout or virtual functions.
#ifdef SOMASIM_PLUGIN_INTERFACE_VERSION_OVERRIDE  // only for the loader's own tests
inline constexpr const char* kPluginInterfaceVersion = SOMASIM_PLUGIN_INTERFACE_VERSION_OVERRIDE;
#else
inline constexpr const char* kPluginInterfaceVersion = "somasim-plugin-api/6";
#endif

/// What `somasim --version` prints: the package version, the plugin interface and the compiler.
inline std::string version_text() {
  return std::string("somasim ") + kVersion + " (plugin interface " + kPluginInterfaceVersion +
         ", compiler " + __VERSION__ + ")";
}

}  // namespace somasim
