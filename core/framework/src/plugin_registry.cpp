#include "somasim/plugin_registry.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <set>

#include "somasim/elf_symbols.hpp"
#include "somasim/error.hpp"
#include "somasim/plugin.hpp"

namespace somasim {
namespace fs = std::filesystem;

namespace {

bool provides(const LibraryCandidate& c, const std::string& name) {
  return std::any_of(c.plugins.begin(), c.plugins.end(),
                     [&](const IndexedPlugin& p) { return p.name == name; });
}

std::string first_line(const std::string& text) {
  return text.substr(0, text.find('\n'));
}

}  // namespace

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

void PluginRegistry::open(LibraryCandidate& c) {
  if (c.opened || c.rejected()) return;
  // dlopen runs the library's constructors: only a file that exports the entry point (read
  // from its dynamic symbols, without loading it) is opened.
  if (std::string why; !elf_exports_function(c.path, SOMASIM_PLUGIN_ENTRY_SYMBOL, why)) {
    c.rejection = why + "; not loaded";
    return;
  }
  // RTLD_LOCAL keeps plugins' symbols apart; libraries stay loaded for the process lifetime
  // because plugin instances and their specs' factories point into them.
  // An absolute path: dlopen searches the library path for a name without '/', and would load
  // another file than the one checked.
  void* handle = dlopen(fs::absolute(c.path).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* err = dlerror();
    c.rejection = std::string("cannot be loaded: ") + (err ? err : "unknown dlopen error");
    return;
  }
  using EntryFn = const PluginLibraryEntry* (*)();
  auto entry_fn = reinterpret_cast<EntryFn>(dlsym(handle, SOMASIM_PLUGIN_ENTRY_SYMBOL));
  if (!entry_fn) {
    c.rejection =
        "no entry point '" SOMASIM_PLUGIN_ENTRY_SYMBOL "' (is SOMASIM_PLUGIN_LIBRARY missing?)";
    dlclose(handle);
    return;
  }
  const PluginLibraryEntry* entry = entry_fn();
  if (!entry || !entry->interface_version || !entry->register_plugins ||
      std::strcmp(entry->interface_version, kPluginInterfaceVersion) != 0) {
    c.rejection = std::string("built for plugin interface '") +
                  (entry && entry->interface_version ? entry->interface_version : "?") +
                  "', this somasim needs '" + kPluginInterfaceVersion + "' (rebuild the plugin)";
    dlclose(handle);
    return;
  }
  PluginRegistrar registrar;
  entry->register_plugins(registrar);
  c.opened = true;
  opened_order_.push_back(c.path);
  // What the library really provides replaces what its index said.
  c.plugins.clear();
  for (auto& spec : registrar.specs()) {
    c.plugins.push_back({spec.name(), first_line(spec.doc())});
    spec.library_path = c.path.string();
    c.specs.try_emplace(spec.name(), std::move(spec));
  }
}

LibraryCandidate PluginRegistry::inspect(const fs::path& file) {
  LibraryCandidate c;
  c.path = file;
  if (auto indexed = read_plugin_index(file, c.index_note)) {
    c.indexed = true;
    c.plugins = std::move(*indexed);
  } else if (std::string why; !elf_exports_function(file, SOMASIM_PLUGIN_ENTRY_SYMBOL, why)) {
    c.rejection = why + "; not loaded";
  }
  // Without a usable index its plugins are unknown until it is opened: only when a plugin is
  // provided by no indexed library (find), or when every plugin is listed (list).
  return c;
}

void PluginRegistry::load_library(const fs::path& file) {
  if (!fs::exists(file)) throw InputError("plugin library '" + file.string() + "' does not exist");
  LibraryCandidate c;
  c.path = file;
  const auto known = std::find_if(candidates_.begin(), candidates_.end(),
                                  [&](const LibraryCandidate& k) { return k.path == file; });
  if (known != candidates_.end()) {
    c = std::move(*known);
    candidates_.erase(known);
  }
  c.index_note = "loaded explicitly";
  open(c);
  const std::string why = c.rejection;
  // Explicit libraries go first: find() resolves in candidate order.
  candidates_.insert(candidates_.begin(), std::move(c));
  if (!why.empty()) throw InputError("plugin library '" + file.string() + "' rejected: " + why);
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
      if (!seen) candidates_.push_back(inspect(f));
    }
  }
}

const PluginSpec* PluginRegistry::find(const std::string& name) {
  scan();
  for (auto& c : candidates_) {
    if (c.rejected() || !provides(c, name)) continue;
    open(c);
    const auto it = c.specs.find(name);
    if (it != c.specs.end()) return &it->second;
    // A stale index named it but the library does not provide it: keep looking.
  }
  // No known library provides it: open the ones without an index, in order, until one does.
  for (auto& c : candidates_) {
    if (c.rejected() || c.indexed || c.opened) continue;
    open(c);
    const auto it = c.specs.find(name);
    if (it != c.specs.end()) return &it->second;
  }
  return nullptr;
}

void PluginRegistry::open_unindexed() {
  scan();
  for (auto& c : candidates_)
    if (!c.indexed) open(c);
}

std::vector<PluginRegistry::Listing> PluginRegistry::list() {
  open_unindexed();
  std::vector<Listing> out;
  std::set<std::string> seen;
  for (const auto& c : candidates_) {
    if (c.rejected()) continue;
    for (const auto& p : c.plugins)
      if (seen.insert(p.name).second) out.push_back({p, &c});
  }
  std::sort(out.begin(), out.end(),
            [](const Listing& a, const Listing& b) { return a.plugin.name < b.plugin.name; });
  return out;
}

std::vector<std::string> PluginRegistry::names() {
  scan();
  std::set<std::string> out;
  for (const auto& c : candidates_)
    if (!c.rejected())
      for (const auto& p : c.plugins) out.insert(p.name);
  return {out.begin(), out.end()};
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
               (c.rejected()              ? " [rejected: " + c.rejection + "]"
                : !c.indexed && !c.opened ? " [no index: not opened]"
                                          : "");
    }
    out += found.empty() ? " (no .so files);" : " (" + found + ");";
  }
  for (const auto& c : candidates_) {
    const bool in_path = std::any_of(search_path_.begin(), search_path_.end(),
                                     [&](const fs::path& d) { return c.path.parent_path() == d; });
    if (!in_path)
      out += " " + c.path.string() +
             (c.rejected() ? " [rejected: " + c.rejection + "];" : " (loaded explicitly);");
  }
  if (!out.empty() && out.back() == ';') out.pop_back();
  return out;
}

void index_plugin_library(const fs::path& library) {
  PluginRegistry registry({});
  registry.load_library(library);
  write_plugin_index(library, registry.candidates().front().plugins);
}

}  // namespace somasim
