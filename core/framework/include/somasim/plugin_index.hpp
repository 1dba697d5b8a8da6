#pragma once
/// @file
/// Plugin index files: a text file next to each plugin library (`<library>.index`) that lists
/// the plugins it provides, so that somasim finds a plugin without loading (dlopen'ing, running
/// the constructors of) every library on the search path. The build writes it
/// (`somasim plugins index LIB`, called by somasim_add_plugin); a library without a valid index
/// is still found, by loading it.
///
/// Format, one entry per line:
///   somasim-plugin-index 1
///   interface <plugin interface version>
///   plugin <name> <first line of its documentation>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace somasim {

/// One plugin as an index lists it.
struct IndexedPlugin {
  std::string name;
  std::string summary;  ///< first line of the plugin's documentation
};

/// The index file of a plugin library: `<library>.index`.
std::filesystem::path plugin_index_path(const std::filesystem::path& library);

/// Reads the index of `library`. Empty (and `why` says why) when there is none, it is older than
/// the library, it is malformed or was written for another plugin interface version.
std::optional<std::vector<IndexedPlugin>> read_plugin_index(const std::filesystem::path& library,
                                                            std::string& why);

/// Writes the index of `library` listing `plugins`. Throws InputError if it cannot be written.
void write_plugin_index(const std::filesystem::path& library,
                        const std::vector<IndexedPlugin>& plugins);

}  // namespace somasim
