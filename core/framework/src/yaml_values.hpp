#pragma once
// Internal: reading typed values out of yaml-cpp nodes with precise messages.
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "somasim/param.hpp"
#include "somasim/source_location.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::detail {

/// Maps yaml-cpp nodes to their source location; nodes created by --set map to the override.
class LocationMap {
 public:
  explicit LocationMap(std::string file) : file_(std::move(file)) {}
  /// `node` and what it holds (a whole node added by --set) are located at the override; at
  /// most 10000 nodes and 64 levels (aliases make a graph, not a tree).
  void add_override(const YAML::Node& node, const std::string& text, int depth = 0) {
    if (depth > 64 || overrides_.size() > 10000) return;
    overrides_.push_back({node, text});
    if (node.IsMap())
      for (const auto& kv : node) add_override(kv.second, text, depth + 1);
    else if (node.IsSequence())
      for (const auto& item : node) add_override(item, text, depth + 1);
  }
  SourceLocation of(const YAML::Node& node) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

using somasim::describe_yaml;
using somasim::parse_bool;
using somasim::parse_double;
using somasim::parse_int;

/// Converts `node` to a value of `spec`'s type and checks range/choices/size. Returns the
/// problem ("expected ..., got ...") on failure.
std::optional<ParamValue> to_param_value(const YAML::Node& node, const ParamSpec& spec,
                                         std::string& problem);

/// "a number [m] in [0, 1]" — what a parameter expects, for messages.
std::string expectation(const ParamSpec& spec);

}  // namespace somasim::detail
