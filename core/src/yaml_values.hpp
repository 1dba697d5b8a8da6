#pragma once
// Internal: reading typed values out of yaml-cpp nodes with precise messages.
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "somasim/param.hpp"
#include "somasim/source_location.hpp"

namespace somasim::detail {

/// Maps yaml-cpp nodes to their source location; nodes created by --set map to the override.
class LocationMap {
 public:
  explicit LocationMap(std::string file) : file_(std::move(file)) {}
  void add_override(const YAML::Node& node, const std::string& text) {
    overrides_.push_back({node, text});
  }
  SourceLocation of(const YAML::Node& node) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

/// A YAML scalar rendered back for messages ("'abc'", "a list", "a map").
std::string describe_yaml(const YAML::Node& node);

/// Converts `node` to a value of `spec`'s type and checks range/choices/size. Returns the
/// problem ("expected ..., got ...") on failure.
std::optional<ParamValue> to_param_value(const YAML::Node& node, const ParamSpec& spec,
                                         std::string& problem);

/// "a number [m] in [0, 1]" — what a parameter expects, for messages.
std::string expectation(const ParamSpec& spec);

/// Strict number parsing of a scalar (no trailing text). NaN/inf are parsed (and rejected later).
std::optional<double> parse_double(const std::string& text);
std::optional<std::int64_t> parse_int(const std::string& text);
std::optional<bool> parse_bool(const std::string& text);

}  // namespace somasim::detail
