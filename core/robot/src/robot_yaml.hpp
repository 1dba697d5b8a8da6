#pragma once
// Internal: reading robot-description YAML with file:line:column messages.
//
// Every message reads "file:line:col: ITEM, key 'KEY': what is wrong; expected ...", where ITEM
// names what is being read ("link 'r_hand'", "chain 'right_arm'", ...). Errors are collected in
// a Diagnostics and thrown together.
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

#include "somasim/diagnostics.hpp"

namespace somasim::robot::detail {

/// Which file (and directory, for relative paths) a YAML node came from. Nodes are in the
/// default file unless they were put in place by an 'extends' + 'set' description.
class NodeOrigins {
 public:
  void set_default(std::string file, std::filesystem::path dir) {
    file_ = std::move(file);
    dir_ = std::move(dir);
  }
  /// Registers `node` and everything below it as written in `file`.
  void add(const YAML::Node& node, const std::string& file, const std::filesystem::path& dir);
  SourceLocation location(const YAML::Node& node) const;
  const std::filesystem::path& directory(const YAML::Node& node) const;
  const std::string& default_file() const { return file_; }

 private:
  struct Entry {
    YAML::Node node;
    std::string file;
    std::filesystem::path dir;
  };
  const Entry* find(const YAML::Node& node) const;
  std::string file_;
  std::filesystem::path dir_;
  std::vector<Entry> entries_;
};

/// "'abc'", "a list", "a map", "nothing".
std::string describe(const YAML::Node& node);

/// Typed reads that report problems into `diags` and return nullopt on failure. `item` names
/// the thing being read ("link 'x'"), `key` the full key path shown in messages.
class YamlReader {
 public:
  YamlReader(Diagnostics& diags, const NodeOrigins& origins) : diags_(diags), origins_(origins) {}

  void error(const YAML::Node& at, const std::string& item, const std::string& key,
             const std::string& message);
  /// Reports keys of `map` not in `allowed` ("unknown key (did you mean ...); expected one of").
  void check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                  const std::string& item, const std::string& prefix);
  /// A map, or reports "expected WHAT, got ..." and returns false.
  bool expect_map(const YAML::Node& node, const std::string& item, const std::string& key,
                  const std::string& what);

  std::optional<std::string> string(const YAML::Node& map, const std::string& key,
                                    const std::string& item, const std::string& prefix,
                                    bool required);
  /// A finite number; `required` → "missing required key" when absent.
  std::optional<double> number(const YAML::Node& map, const std::string& key,
                               const std::string& item, const std::string& prefix, bool required,
                               const std::string& unit = "");
  /// A number > 0 (messages: "expected WHAT > 0 [unit], got X").
  std::optional<double> positive(const YAML::Node& map, const std::string& key,
                                 const std::string& item, const std::string& prefix, bool required,
                                 const std::string& what, const std::string& unit);
  /// An integer in [min, max] ("expected an integer in [min, max]" / ">= min" without a max).
  std::optional<std::int64_t> integer(const YAML::Node& map, const std::string& key,
                                      const std::string& item, const std::string& prefix,
                                      bool required, std::int64_t min,
                                      std::int64_t max = std::numeric_limits<std::int64_t>::max());
  /// A list of exactly n finite numbers.
  std::optional<Eigen::VectorXd> numbers(const YAML::Node& map, const std::string& key,
                                         const std::string& item, const std::string& prefix,
                                         bool required, int n, const std::string& unit = "");
  /// A pose {xyz: [3] m, rpy_deg: [3]} or {matrix: 4×4 rows}; identity when absent.
  std::optional<Eigen::Isometry3d> pose(const YAML::Node& map, const std::string& key,
                                        const std::string& item, const std::string& prefix);

  SourceLocation location(const YAML::Node& node) const { return origins_.location(node); }

 private:
  Diagnostics& diags_;
  const NodeOrigins& origins_;
};

/// Roll-pitch-yaw about fixed x, y, z (URDF): R = Rz(yaw)·Ry(pitch)·Rx(roll) [rad].
Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy);

std::optional<double> parse_number(const std::string& text);

}  // namespace somasim::robot::detail
