#include "robot_yaml.hpp"
#include "somasim/yaml_text.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include "somasim/units.hpp"

namespace somasim::robot::detail {

void NodeOrigins::add(const YAML::Node& node, const std::string& file,
                      const std::filesystem::path& dir) {
  entries_.push_back({node, file, dir});
  if (node.IsMap()) {
    for (const auto& kv : node) {
      entries_.push_back({kv.first, file, dir});
      add(kv.second, file, dir);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) add(item, file, dir);
  }
}

const NodeOrigins::Entry* NodeOrigins::find(const YAML::Node& node) const {
  // Latest first: a value set by a derived file replaces the base file's.
  for (auto it = entries_.rbegin(); it != entries_.rend(); ++it)
    if (it->node.is(node)) return &*it;
  return nullptr;
}

SourceLocation NodeOrigins::location(const YAML::Node& node) const {
  const Entry* e = find(node);
  const std::string& file = e ? e->file : file_;
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {file, 0, 0};
  return {file, mark.line + 1, mark.column + 1};
}

const std::filesystem::path& NodeOrigins::directory(const YAML::Node& node) const {
  const Entry* e = find(node);
  return e ? e->dir : dir_;
}

std::string describe(const YAML::Node& node) {
  return describe_yaml(node);
}

std::optional<double> parse_number(const std::string& text) {
  const auto v = parse_double(text);
  return v && std::isfinite(*v) ? v : std::nullopt;
}

Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

void YamlReader::error(const YAML::Node& at, const std::string& item, const std::string& key,
                       const std::string& message) {
  std::string text = item;
  if (!key.empty()) text += (text.empty() ? "" : ", ") + std::string("key '") + key + "'";
  diags_.add(origins_.location(at), "", "", text.empty() ? message : text + ": " + message);
}

void YamlReader::check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                            const std::string& item, const std::string& prefix) {
  for (const auto& kv : map) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : describe(kv.first);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      // Keys put in place by 'set' have no position: point at their value instead.
      error(
          kv.first.Mark().is_null() ? kv.second : kv.first, item, prefix + key,
          "unknown key" + did_you_mean(key, allowed) + "; expected one of: " + join_names(allowed));
  }
}

bool YamlReader::expect_map(const YAML::Node& node, const std::string& item, const std::string& key,
                            const std::string& what) {
  if (node.IsMap()) return true;
  error(node, item, key, "expected " + what + ", got " + describe(node));
  return false;
}

std::optional<std::string> YamlReader::string(const YAML::Node& map, const std::string& key,
                                              const std::string& item, const std::string& prefix,
                                              bool required) {
  const YAML::Node n = map[key];
  if (!n) {
    if (required) error(map, item, prefix + key, "missing required key (expected a name)");
    return std::nullopt;
  }
  if (!n.IsScalar() || n.Scalar().empty()) {
    error(n, item, prefix + key, "expected a name, got " + describe(n));
    return std::nullopt;
  }
  return n.Scalar();
}

std::optional<double> YamlReader::number(const YAML::Node& map, const std::string& key,
                                         const std::string& item, const std::string& prefix,
                                         bool required, const std::string& unit) {
  const YAML::Node n = map[key];
  const std::string u = unit.empty() ? "" : " [" + unit + "]";
  if (!n) {
    if (required)
      error(map, item, prefix + key, "missing required key (expected a number" + u + ")");
    return std::nullopt;
  }
  const auto v = n.IsScalar() ? parse_number(n.Scalar()) : std::nullopt;
  if (!v) error(n, item, prefix + key, "expected a finite number" + u + ", got " + describe(n));
  return v;
}

std::optional<double> YamlReader::positive(const YAML::Node& map, const std::string& key,
                                           const std::string& item, const std::string& prefix,
                                           bool required, const std::string& what,
                                           const std::string& unit) {
  const auto v = number(map, key, item, prefix, required, unit);
  if (v && *v <= 0) {
    error(map[key], item, prefix + key,
          "expected " + what + " > 0 [" + unit + "], got " + map[key].Scalar());
    return std::nullopt;
  }
  return v;
}

std::optional<std::int64_t> YamlReader::integer(const YAML::Node& map, const std::string& key,
                                                const std::string& item, const std::string& prefix,
                                                bool required, std::int64_t min, std::int64_t max) {
  const std::string expected = max == std::numeric_limits<std::int64_t>::max()
                                   ? fmt::format("an integer >= {}", min)
                                   : fmt::format("an integer in [{}, {}]", min, max);
  const YAML::Node n = map[key];
  if (!n) {
    if (required)
      error(map, item, prefix + key, "missing required key (expected " + expected + ")");
    return std::nullopt;
  }
  std::optional<std::int64_t> v;
  if (n.IsScalar()) {
    char* end = nullptr;
    errno = 0;
    const long long x = std::strtoll(n.Scalar().c_str(), &end, 10);
    if (!n.Scalar().empty() && end == n.Scalar().c_str() + n.Scalar().size() && errno == 0) v = x;
  }
  if (!v || *v < min || *v > max) {
    error(n, item, prefix + key, fmt::format("expected {}, got {}", expected, describe(n)));
    return std::nullopt;
  }
  return v;
}

std::optional<Eigen::VectorXd> YamlReader::numbers(const YAML::Node& map, const std::string& key,
                                                   const std::string& item,
                                                   const std::string& prefix, bool required, int n,
                                                   const std::string& unit) {
  const YAML::Node node = map[key];
  const std::string what =
      fmt::format("a list of {} numbers{}", n, unit.empty() ? "" : " [" + unit + "]");
  if (!node) {
    if (required) error(map, item, prefix + key, "missing required key (expected " + what + ")");
    return std::nullopt;
  }
  if (!node.IsSequence() || static_cast<int>(node.size()) != n) {
    error(node, item, prefix + key,
          "expected " + what + ", got " +
              (node.IsSequence() ? fmt::format("{} items", node.size()) : describe(node)));
    return std::nullopt;
  }
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) {
    const YAML::Node e = node[i];
    const auto v = e.IsScalar() ? parse_number(e.Scalar()) : std::nullopt;
    if (!v) {
      error(e, item, fmt::format("{}{}[{}]", prefix, key, i),
            "expected a finite number, got " + describe(e));
      return std::nullopt;
    }
    out[i] = *v;
  }
  return out;
}

std::optional<Eigen::Isometry3d> YamlReader::pose(const YAML::Node& map, const std::string& key,
                                                  const std::string& item,
                                                  const std::string& prefix) {
  const YAML::Node n = map[key];
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  if (!n) return out;
  const std::string path = prefix + key;
  if (!expect_map(n, item, path, "a pose {xyz: [x, y, z], rpy_deg: [r, p, y]} or {matrix: 4x4}"))
    return std::nullopt;
  check_keys(n, {"xyz", "rpy_deg", "matrix"}, item, path + ".");
  if (n["matrix"]) {
    if (n["xyz"] || n["rpy_deg"]) {
      error(n, item, path, "expected either 'matrix' or 'xyz'/'rpy_deg', got both");
      return std::nullopt;
    }
    const YAML::Node m = n["matrix"];
    if (!m.IsSequence() || m.size() != 4) {
      error(m, item, path + ".matrix", "expected 4 rows of 4 numbers, got " + describe(m));
      return std::nullopt;
    }
    Eigen::Matrix4d t;
    for (int r = 0; r < 4; ++r) {
      const YAML::Node row = m[r];
      if (!row.IsSequence() || row.size() != 4) {
        error(row, item, fmt::format("{}.matrix[{}]", path, r),
              "expected a row of 4 numbers, got " + describe(row));
        return std::nullopt;
      }
      for (int c = 0; c < 4; ++c) {
        const auto v = row[c].IsScalar() ? parse_number(row[c].Scalar()) : std::nullopt;
        if (!v) {
          error(row[c], item, fmt::format("{}.matrix[{}][{}]", path, r, c),
                "expected a finite number, got " + describe(row[c]));
          return std::nullopt;
        }
        t(r, c) = *v;
      }
    }
    const Eigen::Matrix3d rot = t.topLeftCorner<3, 3>();
    if ((rot.transpose() * rot - Eigen::Matrix3d::Identity()).norm() > 1e-6 ||
        rot.determinant() < 0 || (t.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-12) {
      error(m, item, path + ".matrix",
            "not a rigid transform; expected a rotation (orthonormal, determinant +1) and a last "
            "row 0 0 0 1");
      return std::nullopt;
    }
    out.matrix() = t;
    return out;
  }
  const auto xyz = numbers(n, "xyz", item, path + ".", false, 3, "m");
  const auto rpy = numbers(n, "rpy_deg", item, path + ".", false, 3, "deg");
  if ((n["xyz"] && !xyz) || (n["rpy_deg"] && !rpy)) return std::nullopt;
  if (xyz) out.translation() = *xyz;
  if (rpy) out.linear() = rpy_rotation(rpy->unaryExpr([](double d) { return deg_to_rad(d); }));
  return out;
}

}  // namespace somasim::robot::detail
