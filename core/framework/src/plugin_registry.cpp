#include "somasim/plugin_registry.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "somasim/error.hpp"
#include "somasim/plugin.hpp"

namespace somasim {
namespace fs = std::filesystem;

PluginRegistry::PluginRegistry(std::vector<fs::path> search_path)
    : search_path_(std::move(search_path)) {}

std::vector<fs::path> PluginRegistry::default_search_path(const std::vector<fs::path>& cli_paths) {
  std::vector<fs::path> path = cli_paths;
  if (const char* env = std::getenv("SOMASIM_PLUGIN_PATH")) {
    std::string s = env;
    std::size_t start = 0;
    while (start <= s.size()) {
      const std::size_t end = std::min(s.find(':', start), s.size());
      if (end > start) path.emplace_back(s.substr(start, end - start));
      start = end + 1;
    }
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    path.push_back((exe.parent_path() / ".." / "lib" / "somasim" / "plugins").lexically_normal());
  return path;
}

LibraryCandidate PluginRegistry::open(const fs::path& file) {
  LibraryCandidate c;
  c.path = file;
  // RTLD_LOCAL keeps plugins' symbols apart; libraries stay loaded for the process lifetime
  // because plugin instances and their specs' factories point into them.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* err = dlerror();
    c.rejection = std::string("cannot be loaded: ") + (err ? err : "unknown dlopen error");
    return c;
  }
  using EntryFn = const PluginLibraryEntry* (*)();
  auto entry_fn = reinterpret_cast<EntryFn>(dlsym(handle, SOMASIM_PLUGIN_ENTRY_SYMBOL));
  if (!entry_fn) {
    c.rejection =
        "no entry point '" SOMASIM_PLUGIN_ENTRY_SYMBOL "' (is SOMASIM_PLUGIN_LIBRARY missing?)";
    dlclose(handle);
    return c;
  }
  const PluginLibraryEntry* entry = entry_fn();
  if (!entry || !entry->interface_version ||
      std::strcmp(entry->interface_version, kPluginInterfaceVersion) != 0) {
    c.rejection = std::string("built for plugin interface '") +
                  (entry && entry->interface_version ? entry->interface_version : "?") +
                  "', this somasim needs '" + kPluginInterfaceVersion + "' (rebuild the plugin)";
    dlclose(handle);
    return c;
  }
  PluginRegistrar registrar;
  entry->register_plugins(registrar);
  c.loaded = true;
  for (auto& spec : registrar.specs()) {
    c.plugins.push_back(spec.name());
    spec.library_path = file.string();
    // First found wins: the search path's order is the user's order of preference.
    plugins_.try_emplace(spec.name(), std::move(spec));
  }
  return c;
}

void PluginRegistry::load_library(const fs::path& file) {
  for (const auto& c : candidates_)
    if (c.path == file && c.loaded) return;
  if (!fs::exists(file)) throw InputError("plugin library '" + file.string() + "' does not exist");
  LibraryCandidate c = open(file);
  const bool ok = c.loaded;
  const std::string why = c.rejection;
  candidates_.push_back(std::move(c));
  if (!ok) throw InputError("plugin library '" + file.string() + "' rejected: " + why);
}

void PluginRegistry::scan() {
  if (scanned_) return;
  scanned_ = true;
  for (const auto& dir : search_path_) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".so") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const bool seen = std::any_of(candidates_.begin(), candidates_.end(),
                                    [&](const LibraryCandidate& c) { return c.path == f; });
      if (!seen) candidates_.push_back(open(f));
    }
  }
}

const PluginSpec* PluginRegistry::find(const std::string& name) {
  auto it = plugins_.find(name);
  if (it != plugins_.end()) return &it->second;
  scan();
  it = plugins_.find(name);
  return it == plugins_.end() ? nullptr : &it->second;
}

std::vector<const PluginSpec*> PluginRegistry::all() {
  scan();
  std::vector<const PluginSpec*> out;
  for (const auto& [name, spec] : plugins_) out.push_back(&spec);
  return out;
}

std::vector<std::string> PluginRegistry::names() {
  scan();
  std::vector<std::string> out;
  for (const auto& [name, spec] : plugins_) out.push_back(name);
  return out;
}

std::string PluginRegistry::search_report() {
  scan();
  std::string out = "searched:";
  if (search_path_.empty()) out += " (empty search path)";
  for (const auto& dir : search_path_) {
    std::error_code ec;
    out += ' ';  // (not `" " + dir.string()`: GCC 12 warns falsely on it, -Wrestrict)
    out += dir.string();
    if (!fs::is_directory(dir, ec)) {
      out += " (not a directory);";
      continue;
    }
    std::string found;
    for (const auto& c : candidates_) {
      if (c.path.parent_path() != dir) continue;
      found += (found.empty() ? "" : ", ") + c.path.filename().string() +
               (c.loaded ? "" : " [rejected: " + c.rejection + "]");
    }
    out += found.empty() ? " (no .so files);" : " (" + found + ");";
  }
  for (const auto& c : candidates_) {
    const bool in_path = std::any_of(search_path_.begin(), search_path_.end(),
                                     [&](const fs::path& d) { return c.path.parent_path() == d; });
    if (!in_path)
      out += " " + c.path.string() +
             (c.loaded ? " (loaded explicitly);" : " [rejected: " + c.rejection + "];");
  }
  if (!out.empty() && out.back() == ';') out.pop_back();
  return out;
}

}  // namespace somasim
