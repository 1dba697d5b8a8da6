// Robot description loader: documents, extends and set.

#include <sstream>

#include "robot_loader_internal.hpp"
#include "somasim/yaml_text.hpp"
#include "urdf_import.hpp"

namespace somasim::robot::detail {

namespace {

constexpr int kMaxExtendsDepth = 8;
const std::vector<std::string> kExtendsKeys = {"robot", "extends", "set", "missing_meshes"};

}  // namespace

YAML::Node RobotLoader::parse(const std::string& text, const std::string& display) {
  try {
    return load_one_document(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", display, e.mark.line + 1,
                                 e.mark.column + 1, e.msg));
  } catch (const InputError& e) {
    throw InputError(display + ": " + e.what());
  }
}

YAML::Node RobotLoader::resolve(const std::string& text, const std::string& display,
                                const fs::path& dir, int depth, std::vector<fs::path> chain) {
  YAML::Node root = parse(text, display);
  origins_.set_default(display, dir);
  if (!root.IsMap()) {
    reader_.error(root, "", "",
                  "expected a robot description (a map with 'robot', 'links', 'chains', ...), "
                  "got " +
                      describe(root));
    diags_.throw_if_any();
  }
  check_duplicate_keys(root);
  const YAML::Node ext = root["extends"];
  if (!ext) return root;
  reader_.check_keys(root, kExtendsKeys, "", "");
  if (!ext.IsScalar() || ext.Scalar().empty()) {
    reader_.error(ext, "", "extends", "expected a robot description file, got " + describe(ext));
    diags_.throw_if_any();
  }
  const fs::path base_path = (dir / ext.Scalar()).lexically_normal();
  const std::string base_display = (fs::path(display).parent_path() / ext.Scalar()).string();
  chain.push_back(fs::absolute(dir / fs::path(display).filename()).lexically_normal());
  if (depth >= kMaxExtendsDepth ||
      std::find(chain.begin(), chain.end(), fs::absolute(base_path)) != chain.end()) {
    reader_.error(ext, "", "extends",
                  "'" + ext.Scalar() + "' extends itself (directly or through other files)");
    diags_.throw_if_any();
  }
  bool ok = false;
  std::string base_text = read_text(base_path, ok);
  if (!ok) {
    reader_.error(ext, "", "extends",
                  "cannot read '" + ext.Scalar() + "' (resolved to '" + base_path.string() +
                      "'); expected a readable robot description file");
    diags_.throw_if_any();
  }
  MissingMeshes missing = MissingMeshes::kError;
  if (const YAML::Node policy = root["missing_meshes"]; policy) {
    const auto parsed = policy.IsScalar() ? parse_missing_meshes(policy.Scalar()) : std::nullopt;
    if (!parsed)
      reader_.error(policy, "", "missing_meshes",
                    "expected error, skip or collision, got " + describe(policy));
    else if (!is_urdf_file(base_path))
      reader_.error(policy, "", "missing_meshes",
                    "only a file that extends a URDF (.urdf) chooses what missing meshes do");
    else
      missing = *parsed;
    diags_.throw_if_any();
  }
  // A URDF robot that this file completes (cameras, skin, ...): what the loader finds wrong in
  // the converted description is located in the conversion, not in the URDF's lines.
  const bool urdf = is_urdf_file(base_path);
  if (urdf)
    base_text = urdf_to_description(base_text, base_display, base_path.parent_path(), missing);
  YAML::Node base =
      resolve(base_text, urdf ? base_display + " (as converted from URDF)" : base_display,
              base_path.parent_path(), depth + 1, chain);
  // Values of this file are located in this file, the rest in the base.
  if (const YAML::Node name = root["robot"]; name) {
    base["robot"] = name;
    origins_.add(base["robot"], display, dir);
  }
  if (const YAML::Node set = root["set"]; set) {
    if (!reader_.expect_map(set, "", "set", "a map of dotted paths to values")) return base;
    origins_.add(set, display, dir);
    for (const auto& kv : set) apply_set(base, kv.first, kv.second, display, dir, base_display);
  }
  return base;
}

void RobotLoader::apply_set(YAML::Node base, const YAML::Node& key, const YAML::Node& value,
                            const std::string& display, const fs::path& dir,
                            const std::string& base_file) {
  const std::string path = key.Scalar();
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  const std::string shown = "set." + path;
  if (parts.empty() ||
      std::any_of(parts.begin(), parts.end(), [](const auto& p) { return p.empty(); })) {
    reader_.error(key, "", shown, "expected a dotted path such as chains.NAME.links.7.d");
    return;
  }
  YAML::Node node = base;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const bool last = i + 1 == parts.size();
    const std::string walked =
        fmt::format("{}", fmt::join(parts.begin(), parts.begin() + static_cast<long>(i) + 1, "."));
    if (node.IsSequence()) {
      const auto index = detail::parse_number(parts[i]);
      if (!index || *index < 0 || *index != std::floor(*index) ||
          *index >= static_cast<double>(node.size())) {
        reader_.error(key, "", shown,
                      fmt::format("'{}' is a list of {} items in {}; expected an index 0..{}",
                                  walked.substr(0, walked.rfind('.')), node.size(), base_file,
                                  node.size() - 1));
        return;
      }
      const auto at = static_cast<std::size_t>(*index);
      if (last) {
        node[at] = value;
        origins_.add(node[at], display, dir);
        return;
      }
      node.reset(node[at]);
    } else if (node.IsMap()) {
      if (last) {
        node[parts[i]] = value;
        origins_.add(node[parts[i]], display, dir);
        return;
      }
      if (!node[parts[i]]) {
        std::vector<std::string> keys;
        for (const auto& kv : node) keys.push_back(kv.first.Scalar());
        reader_.error(key, "", shown,
                      "no key '" + walked + "' in " + base_file + did_you_mean(parts[i], keys));
        return;
      }
      node.reset(node[parts[i]]);
    } else {
      reader_.error(key, "", shown,
                    "'" + walked.substr(0, walked.rfind('.')) + "' in " + base_file +
                        " is a single value; expected a path into maps and lists");
      return;
    }
  }
}

void RobotLoader::check_duplicate_keys(const YAML::Node& n) {
  if (n.IsSequence())
    for (const auto& item : n) check_duplicate_keys(item);
  if (!n.IsMap()) return;
  std::map<std::string, SourceLocation> seen;
  for (const auto& kv : n) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
    if (auto it = seen.find(key); it != seen.end())
      reader_.error(kv.first, "", key, "duplicate key (first defined at " + it->second.str() + ")");
    else
      seen[key] = reader_.location(kv.first);
    check_duplicate_keys(kv.second);
  }
}

}  // namespace somasim::robot::detail
