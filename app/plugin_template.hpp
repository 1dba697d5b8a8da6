#pragma once
// `somasim plugin new NAME`: a plugin folder to start from, built against the installed package
// (or the build tree), with a harness test.
#include <filesystem>
#include <map>
#include <string>

namespace somasim::app {

/// File name → text of a new plugin folder for plugin `name` (lower-case letters, digits and
/// '_', starting with a letter): CMakeLists.txt, NAME.cpp, test_NAME.cpp, README.md.
/// Throws InputError for a name that is not one.
std::map<std::string, std::string> plugin_template_files(const std::string& name);

/// Writes the folder `dir` (default: ./NAME). InputError for a bad name or an existing
/// non-empty folder (the caller prints it, exit 2).
int cmd_plugin_new(const std::string& name, const std::filesystem::path& dir);

}  // namespace somasim::app
