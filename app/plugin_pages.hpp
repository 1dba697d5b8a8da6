#pragma once
// The generated plugin reference: one Markdown page per plugin library (its plugins'
// parameters with type, unit, default, range and doc; their ports with types) and an index.
#include <filesystem>
#include <map>
#include <string>

#include "somasim/plugin_registry.hpp"

namespace somasim::app {

/// File name (e.g. "somasim_pps.md", "README.md") → page text, for every plugin library the
/// registry finds (each library is opened to read its specs).
std::map<std::string, std::string> plugin_reference_pages(PluginRegistry& registry);

/// `somasim plugins reference DIR [--check]`: writes the pages into DIR (removing generated
/// pages of libraries that are gone), or with `check` compares and lists what differs (exit 1).
int cmd_plugin_reference(PluginRegistry& registry, const std::filesystem::path& dir, bool check);

}  // namespace somasim::app
