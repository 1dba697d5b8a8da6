#pragma once
/// @file
/// Finds plugin shared libraries on a search path, checks their interface version and
/// exposes the plugins they register. Built-in plugins are found the same way as users'.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "somasim/plugin_spec.hpp"

namespace somasim {

/// What the loader found in one file, for error messages and `somasim plugins`.
struct LibraryCandidate {
  std::filesystem::path path;
  bool loaded = false;
  std::string rejection;             ///< why it was rejected (empty when loaded)
  std::vector<std::string> plugins;  ///< names it provides (when loaded)
};

class PluginRegistry {
 public:
  /// `search_path`: directories scanned (in order) for `*.so` files on first lookup.
  explicit PluginRegistry(std::vector<std::filesystem::path> search_path);
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  /// The default search path: `cli_paths`, then each entry of $SOMASIM_PLUGIN_PATH
  /// (colon-separated), then the plugin directory next to the running executable
  /// (`<exe>/../lib/somasim/plugins`, both in the build tree and when installed).
  static std::vector<std::filesystem::path> default_search_path(
      const std::vector<std::filesystem::path>& cli_paths);

  /// Loads one library explicitly (e.g. `plugin_libraries:` in an experiment). Throws
  /// InputError saying why it was rejected.
  void load_library(const std::filesystem::path& file);

  /// The plugin registered under `name`, or nullptr (after scanning the search path).
  const PluginSpec* find(const std::string& name);
  /// Every plugin found (scans the search path).
  std::vector<const PluginSpec*> all();
  /// Names of all plugins found.
  std::vector<std::string> names();
  /// "searched: DIR (...), DIR (...)": what was looked at and why candidates were rejected.
  std::string search_report();

  const std::vector<std::filesystem::path>& search_path() const { return search_path_; }
  const std::vector<LibraryCandidate>& candidates() {
    scan();
    return candidates_;
  }

 private:
  void scan();
  LibraryCandidate open(const std::filesystem::path& file);
  std::vector<std::filesystem::path> search_path_;
  std::vector<LibraryCandidate> candidates_;
  std::map<std::string, PluginSpec> plugins_;
  bool scanned_ = false;
};

}  // namespace somasim
