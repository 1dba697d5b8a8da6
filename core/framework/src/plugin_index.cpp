#include "somasim/plugin_index.hpp"

#include <fstream>
#include <sstream>

#include "somasim/error.hpp"
#include "somasim/plugin.hpp"

namespace somasim {
namespace fs = std::filesystem;

namespace {
constexpr const char* kIndexHeader = "somasim-plugin-index 1";
}  // namespace

fs::path plugin_index_path(const fs::path& library) {
  fs::path p = library;
  p += ".index";
  return p;
}

std::optional<std::vector<IndexedPlugin>> read_plugin_index(const fs::path& library,
                                                            std::string& why) {
  const fs::path file = plugin_index_path(library);
  std::error_code ec;
  const auto index_time = fs::last_write_time(file, ec);
  if (ec) {
    why = "no index";
    return std::nullopt;
  }
  const auto library_time = fs::last_write_time(library, ec);
  if (ec || index_time < library_time) {
    why = "index older than the library";
    return std::nullopt;
  }
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line) || line != kIndexHeader) {
    why = "index is not a somasim plugin index";
    return std::nullopt;
  }
  if (!std::getline(in, line) || line != std::string("interface ") + kPluginInterfaceVersion) {
    why = "index written for another plugin interface";
    return std::nullopt;
  }
  std::vector<IndexedPlugin> plugins;
  while (std::getline(in, line)) {
    std::istringstream is(line);
    std::string keyword;
    IndexedPlugin p;
    if (!(is >> keyword >> p.name) || keyword != "plugin") {
      why = "malformed index line '" + line + "'";
      return std::nullopt;
    }
    std::getline(is >> std::ws, p.summary);
    plugins.push_back(std::move(p));
  }
  return plugins;
}

void write_plugin_index(const fs::path& library, const std::vector<IndexedPlugin>& plugins) {
  const fs::path file = plugin_index_path(library);
  std::ofstream out(file, std::ios::trunc);
  out << kIndexHeader << "\ninterface " << kPluginInterfaceVersion << '\n';
  for (const auto& p : plugins) out << "plugin " << p.name << ' ' << p.summary << '\n';
  out.close();
  if (!out) throw InputError("cannot write plugin index '" + file.string() + "'");
}

}  // namespace somasim
