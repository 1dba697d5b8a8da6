#pragma once
/// @file
/// Finds plugin shared libraries on a search path, checks their interface version and
/// exposes the plugins they register. Built-in plugins are found the same way as users'.
///
/// Libraries are loaded (dlopen'ed, which runs their constructors) only when needed, and only
/// files that export the entry point (read from their ELF dynamic symbols, elf_symbols.hpp):
/// a library with a valid index file (plugin_index.hpp) is opened when one of its plugins is
/// looked up; a library without one only when no indexed library provides the plugin looked up,
/// or when every plugin is listed (`somasim plugins`). An explicit library (load_library) is
/// opened at once: the experiment that names it trusts it as it would a script.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "somasim/plugin_index.hpp"
#include "somasim/plugin_spec.hpp"

namespace somasim {

/// What the registry knows of one library file, for lookups, errors and `somasim plugins`.
struct LibraryCandidate {
  std::filesystem::path path;
  bool indexed = false;                     ///< its plugins are known from its index file
  bool opened = false;                      ///< dlopen'ed (and accepted) in this process
  std::string rejection;                    ///< why it was rejected (empty unless rejected)
  std::string index_note;                   ///< why its index was not used (when not indexed)
  std::vector<IndexedPlugin> plugins;       ///< what it provides (from the index or the library)
  std::map<std::string, PluginSpec> specs;  ///< its registered plugins (once opened)

  bool rejected() const { return !rejection.empty(); }
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

  /// Loads one library explicitly (e.g. `plugin_libraries:` in an experiment); its plugins take
  /// precedence over the search path's. Throws InputError saying why it was rejected.
  void load_library(const std::filesystem::path& file);

  /// The plugin registered under `name`, or nullptr. The first library (explicit ones, then the
  /// search path in order) that provides it wins; only that library is opened.
  const PluginSpec* find(const std::string& name);
  /// Every plugin found, each once (as find() would resolve it), without opening indexed
  /// libraries (libraries without an index are opened to see what they provide): name,
  /// summary and library.
  struct Listing {
    IndexedPlugin plugin;
    const LibraryCandidate* library = nullptr;
  };
  std::vector<Listing> list();
  /// Names of the plugins known without opening anything more (indexed and opened libraries).
  std::vector<std::string> names();
  /// "searched: DIR (...), DIR (...)": what was looked at and why candidates were rejected.
  std::string search_report();
  /// The libraries dlopen'ed so far, in the order they were opened.
  std::vector<std::filesystem::path> opened_libraries() const { return opened_order_; }

  const std::vector<std::filesystem::path>& search_path() const { return search_path_; }
  const std::vector<LibraryCandidate>& candidates() {
    scan();
    return candidates_;
  }

 private:
  void scan();
  LibraryCandidate inspect(const std::filesystem::path& file);
  void open(LibraryCandidate& c);
  void open_unindexed();
  std::vector<std::filesystem::path> search_path_;
  std::vector<LibraryCandidate> candidates_;
  std::vector<std::filesystem::path> opened_order_;
  bool scanned_ = false;
};

/// Opens `library` and writes its index file (what `somasim plugins index` does). Throws
/// InputError when the library is rejected or the index cannot be written.
void index_plugin_library(const std::filesystem::path& library);

}  // namespace somasim
