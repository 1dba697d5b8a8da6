#pragma once
// Internal: a YAML value as the one-line text `--set PATH=VALUE` reads back to the same value.
#include <string>

#include <yaml-cpp/yaml.h>

namespace somasim::sweep {

/// Plain scalars as written; other scalars, lists and maps in flow style, quoted where needed.
std::string yaml_value_text(const YAML::Node& node);

}  // namespace somasim::sweep
