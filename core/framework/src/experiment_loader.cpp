// Loading an experiment file: YAML → overrides → schema validation → wiring checks.
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "graph_check.hpp"
#include "somasim/config.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/numeric.hpp"
#include "somasim/plugin_registry.hpp"
#include "yaml_values.hpp"

namespace somasim {
namespace fs = std::filesystem;
using detail::describe_yaml;
using detail::LocationMap;

namespace {

const std::vector<std::string> kTopKeys = {
    "experiment", "description",      "seed",   "duration_s", "base_rate_hz",
    "base_dir",   "plugin_libraries", "robots", "nodes",      "record"};
const std::vector<std::string> kNodeKeys = {"plugin", "rate_hz", "params", "inputs", "description"};
const std::vector<std::string> kWireKeys = {"from", "delayed"};
// yaml-cpp holds ~200 bytes per byte of a file of tiny keys (measured: 16 MB of 'c: 1' lines took
// 3.0 GB and 13.6 s); 2 MiB bounds that to ~400 MB, ~600 times the largest shipped experiment.
constexpr std::uintmax_t kMaxExperimentFileBytes = 2u << 20;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) parts.push_back(item);
  return parts;
}

class Loader {
 public:
  Loader(std::string display_name, fs::path base_dir, PluginRegistry& registry,
         const LoadOptions& options)
      : locs_(display_name), registry_(registry), options_(options) {
    exp_.file = display_name;
    exp_.base_dir = std::move(base_dir);
  }

  Experiment load(const std::string& text) {
    YAML::Node root;
    try {
      root = load_one_document(text);
    } catch (const YAML::ParserException& e) {
      throw InputError(syntax_error_message(text, e));
    } catch (const InputError& e) {
      throw InputError(locs_.file() + ": " + e.what());
    }
    if (!root.IsMap()) {
      throw InputError(
          locs_.of(root).str() +
          ": expected a map with the keys 'experiment', 'duration_s' and 'nodes', got " +
          describe_yaml(root));
    }
    apply_overrides(root);
    // Before anything reads a key as text: keys that are not plain scalars end the load here.
    check_keys(root, {});
    if (bad_keys_) diags_.throw_if_any();
    read_top(root);
    detail::check_graph(exp_, diags_, options_.allow_harness_inputs);
    diags_.throw_if_any();
    return std::move(exp_);
  }

 private:
  // yaml-cpp's messages for the two commonest slips point at the wrong place or say little: a
  // tab in the indentation ("illegal map value"), and an unclosed bracket (found at the end).
  std::string syntax_error_message(const std::string& text, const YAML::ParserException& e) {
    int line = 1;
    std::size_t line_start = 0;
    struct Bracket {
      char c;
      int line, column;
    };
    std::vector<Bracket> open;  // unclosed [ and {
    char quote = 0;
    bool comment = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      if (c == '\n') {
        ++line;
        line_start = i + 1;
        comment = false;
        if (quote) quote = 0;  // flow scalars spanning lines are rare here; do not guess
        continue;
      }
      const bool in_indent = text.find_first_not_of(" \t", line_start) >= i;
      if (c == '\t' && in_indent && !quote)
        return fmt::format("{}:{}:{}: a tab in the indentation; YAML indents with spaces only",
                           locs_.file(), line, i - line_start + 1);
      if (comment) continue;
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '\'' || c == '"') {
        quote = c;
      } else if (c == '#' && (i == line_start || text[i - 1] == ' ')) {
        comment = true;
      } else if (c == '[' || c == '{') {
        open.push_back({c, line, static_cast<int>(i - line_start) + 1});
      } else if (!open.empty() &&
                 ((c == ']' && open.back().c == '[') || (c == '}' && open.back().c == '{'))) {
        open.pop_back();
      }
    }
    std::string msg = fmt::format("{}:{}:{}: YAML syntax error: {}", locs_.file(), e.mark.line + 1,
                                  e.mark.column + 1, e.msg);
    if (!open.empty())
      msg += fmt::format(" (the '{}' opened at {}:{}:{} is never closed)", open.back().c,
                         locs_.file(), open.back().line, open.back().column);
    return msg;
  }

  void error(const YAML::Node& at, const std::string& node, const std::string& key,
             const std::string& msg) {
    diags_.add(locs_.of(at), node, key, msg);
  }

  // yaml-cpp keeps every duplicate key in map iteration, but lookups return the first one: a
  // repeated key would silently lose its value. Node names have their own message (read_nodes).
  // Keys must be plain scalars. An alias is the node it names: each node is visited once, so
  // aliases of aliases ("billion laughs") cost what the file costs, not what they expand to.
  void check_keys(const YAML::Node& n, const std::vector<std::string>& path) {
    if (!n.IsSequence() && !n.IsMap()) return;
    if (const YAML::Mark m = n.Mark(); !m.is_null() && !visited_.insert({m.pos, m.line}).second)
      return;
    if (n.IsSequence())
      for (const auto& item : n) check_keys(item, path);
    if (!n.IsMap()) return;
    const bool node_names = path.size() == 1 && path[0] == "nodes";
    std::map<std::string, SourceLocation> seen;
    for (const auto& kv : n) {
      if (!kv.first.IsScalar()) {
        std::string dotted;
        for (const auto& p : path) dotted += (dotted.empty() ? "" : ".") + p;
        error(kv.first, "", dotted.empty() ? "(top level)" : dotted,
              "keys must be plain names, got " + describe_yaml(kv.first) + " as a key");
        bad_keys_ = true;
        continue;
      }
      const std::string key = kv.first.Scalar();
      std::vector<std::string> sub = path;
      sub.push_back(key);
      if (!node_names) {
        if (auto it = seen.find(key); it != seen.end()) {
          const bool in_node = sub.size() > 2 && sub[0] == "nodes";
          std::string dotted;
          for (std::size_t i = in_node ? 2 : 0; i < sub.size(); ++i)
            dotted += (dotted.empty() ? "" : ".") + sub[i];
          error(kv.first, in_node ? sub[1] : "", dotted,
                "duplicate key (first defined at " + it->second.str() + ")");
          continue;
        }
        seen[key] = locs_.of(kv.first);
      }
      check_keys(kv.second, sub);
    }
  }

  // --- overrides -------------------------------------------------------------------------
  void apply_overrides(YAML::Node& root) {
    for (const auto& ov : options_.overrides) {
      const std::string shown = ov.path + "=" + ov.value;
      const auto fail = [&](const std::string& msg) {
        throw InputError("--set '" + shown + "': " + msg);
      };
      const std::vector<std::string> parts = split(ov.path, '.');
      if (parts.empty() ||
          std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
        fail("expected a dotted path such as nodes.NODE.params.NAME");
      YAML::Node value;
      try {
        value = load_one_document(ov.value);
      } catch (const YAML::ParserException& e) {
        fail("the value is not valid YAML: " + e.msg);
      } catch (const InputError& e) {
        fail(std::string("the value ") + e.what());
      }
      // Walk to the parent map, checking that each step exists.
      YAML::Node parent = root;
      std::string walked;
      for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
        YAML::Node next = parent[parts[i]];
        // A node written without parameters gets its `params` map from the first --set of one.
        if (i == 2 && parts[0] == "nodes" && parts[2] == "params" && !next.IsDefined() &&
            parent.IsMap()) {
          parent[parts[i]] = YAML::Node(YAML::NodeType::Map);
          next = parent[parts[i]];
        }
        if (!next.IsDefined() || !next.IsMap()) {
          std::vector<std::string> keys;
          if (parent.IsMap())
            for (const auto& kv : parent)
              if (kv.first.IsScalar()) keys.push_back(kv.first.Scalar());
          fail("no map '" + (walked.empty() ? "" : walked + ".") + parts[i] + "' in " +
               locs_.file() + did_you_mean(parts[i], keys));
        }
        walked += (walked.empty() ? "" : ".") + parts[i];
        parent.reset(next);
      }
      const std::string& key = parts.back();
      // A whole new node (e.g. a spectator added to any config): its value names its plugin.
      const YAML::Node& as_const = value;
      const bool new_node =
          parts.size() == 2 && parts[0] == "nodes" && value.IsMap() && as_const["plugin"];
      if (!parent[key].IsDefined() && !new_node) {
        const std::vector<std::string> allowed = allowed_new_keys(root, parts);
        if (parts.size() == 2 && parts[0] == "nodes")
          fail("there is no node '" + key + "' in " + locs_.file() + did_you_mean(key, allowed) +
               "; a new node is added by a map with its plugin, e.g. --set 'nodes." + key +
               "={plugin: NAME, inputs: {...}}'");
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
          fail("'" + ov.path + "' does not exist in " + locs_.file() +
               " and is not a key that can be set there" + did_you_mean(key, allowed));
      }
      parent[key] = value;
      locs_.add_override(parent[key], shown);
    }
  }

  // Keys that may be added by --set although absent from the file.
  std::vector<std::string> allowed_new_keys(const YAML::Node& root,
                                            const std::vector<std::string>& parts) {
    if (parts.size() == 1) return kTopKeys;
    if (parts.size() == 2 && parts[0] == "nodes") {  // the existing nodes, for did_you_mean
      std::vector<std::string> names;
      for (const auto& kv : root["nodes"])
        if (kv.first.IsScalar()) names.push_back(kv.first.Scalar());
      return names;
    }
    if (parts.size() == 3 && parts[0] == "nodes") return kNodeKeys;
    if (parts.size() == 4 && parts[0] == "nodes" && parts[2] == "params") {
      const YAML::Node plugin = root["nodes"][parts[1]]["plugin"];
      if (plugin.IsScalar())
        if (const PluginSpec* spec = registry_.find(plugin.Scalar())) return spec->param_names();
    }
    return {};
  }

  // --- top level -------------------------------------------------------------------------
  void read_top(const YAML::Node& root) {
    for (const auto& kv : root) {
      const std::string key = kv.first.as<std::string>();
      if (std::find(kTopKeys.begin(), kTopKeys.end(), key) == kTopKeys.end())
        error(kv.first, "", key,
              "unknown key" + did_you_mean(key, kTopKeys) +
                  "; expected one of: " + join_names(kTopKeys));
    }
    exp_.name = read_string(root, "experiment", options_.defaults_for_tests ? "test" : "");
    // The name makes the default run folder (runs/NAME): nothing that could leave it.
    if (!exp_.name.empty() && !safe_file_name(exp_.name))
      error(root["experiment"], "", "experiment",
            "expected a name of letters, digits, '_' and '-', got " +
                describe_yaml(root["experiment"]));
    if (const YAML::Node d = root["description"]; d)
      exp_.description = read_string(root, "description", "");
    exp_.seed = read_seed(root);
    if (options_.seed) exp_.seed = *options_.seed;
    exp_.duration_s =
        read_number(root, "duration_s", options_.defaults_for_tests ? 1e9 : -1.0, 1e-9, false);
    exp_.base_rate_hz = read_number(root, "base_rate_hz", 1000.0, 1e-9, false);
    check_tick_count(root);
    if (const YAML::Node b = root["base_dir"]; b) exp_.base_dir = read_string(root, "base_dir", "");
    read_libraries(root);
    read_robots(root);
    read_nodes(root);
    read_records(root);
  }

  // The seed is a 64-bit unsigned integer, read exactly (not through a double).
  std::uint64_t read_seed(const YAML::Node& root) {
    const YAML::Node n = root["seed"];
    if (!n) return 0;
    const auto seed = n.IsScalar() ? somasim::parse_seed(n.Scalar()) : std::nullopt;
    if (!seed)
      error(n, "", "seed",
            std::string("expected ") + kSeedExpectation + ", got " + describe_yaml(n));
    return seed.value_or(0);
  }

  // The run has duration_s × base_rate_hz ticks: it must be a count a tick counter (and a
  // double, for times) holds exactly.
  void check_tick_count(const YAML::Node& root) {
    const double ticks = exp_.duration_s * exp_.base_rate_hz;
    if (ticks > kMaxTicks)
      error(root["duration_s"] ? root["duration_s"] : root, "", "duration_s",
            fmt::format("duration_s × base_rate_hz is {:g} ticks; at most {:g} (2^53) can run",
                        ticks, kMaxTicks));
    else if (ticks > 0.0 && std::floor(ticks + 1e-9) < 1.0)  // (<= 0: already refused)
      error(root["duration_s"] ? root["duration_s"] : root, "", "duration_s",
            fmt::format("duration_s × base_rate_hz is {:g} ticks; a run needs at least one tick "
                        "(1 / base_rate_hz = {:g} s)",
                        ticks, 1.0 / exp_.base_rate_hz));
  }
  static constexpr double kMaxTicks = 9007199254740992.0;  // 2^53

  std::string read_string(const YAML::Node& map, const std::string& key,
                          const std::string& fallback) {
    const YAML::Node n = map[key];
    if (!n) {
      if (fallback.empty()) error(map, "", key, "missing required key (expected a string)");
      return fallback;
    }
    if (!n.IsScalar() || n.Scalar().empty()) {
      error(n, "", key, "expected a string, got " + describe_yaml(n));
      return fallback;
    }
    return n.Scalar();
  }

  // Reads a finite number >= min; fallback < 0 means required. integer: must be integral.
  double read_number(const YAML::Node& map, const std::string& key, double fallback, double min,
                     bool integer) {
    const YAML::Node n = map[key];
    const char* what = integer ? "an integer" : "a number";
    if (!n) {
      if (fallback < 0)
        error(map, "", key, std::string("missing required key (expected ") + what + ")");
      return std::max(fallback, 0.0);
    }
    const auto v = n.IsScalar() ? (integer ? [&]() -> std::optional<double> {
      auto i = detail::parse_int(n.Scalar());
      return i ? std::optional<double>(static_cast<double>(*i)) : std::nullopt;
    }() : detail::parse_double(n.Scalar())) : std::nullopt;
    if (!v) {
      error(n, "", key, std::string("expected ") + what + ", got " + describe_yaml(n));
    } else if (!std::isfinite(*v)) {
      error(n, "", key, "expected a finite number, got " + describe_yaml(n));
    } else if (*v < min || (min > 0 && *v <= 0)) {
      error(n, "", key,
            fmt::format("expected {} {} 0, got {}", what, min > 0 ? ">" : ">=", n.Scalar()));
    } else {
      return *v;
    }
    return std::max(fallback, 0.0);
  }

  void read_libraries(const YAML::Node& root) {
    const YAML::Node libs = root["plugin_libraries"];
    if (!libs) return;
    if (!libs.IsSequence()) {
      error(libs, "", "plugin_libraries", "expected a list of paths, got " + describe_yaml(libs));
      return;
    }
    for (const auto& item : libs) {
      if (!item.IsScalar()) {
        error(item, "", "plugin_libraries", "expected a path, got " + describe_yaml(item));
        continue;
      }
      fs::path p = item.Scalar();
      if (p.is_relative()) p = exp_.base_dir / p;
      p = p.lexically_normal();
      try {
        registry_.load_library(p);
        exp_.plugin_libraries.push_back(p.string());
      } catch (const InputError& e) {
        error(item, "", "plugin_libraries", e.what());
      }
    }
  }

  // --- robots ----------------------------------------------------------------------------
  // NAME: FILE; the file must exist (the robot library reads it when a node first asks).
  void read_robots(const YAML::Node& root) {
    const YAML::Node robots = root["robots"];
    if (!robots) return;
    if (!robots.IsMap()) {
      error(robots, "", "robots",
            "expected a map of robot names to description files, got " + describe_yaml(robots));
      return;
    }
    for (const auto& kv : robots) {
      const std::string name = kv.first.IsScalar() ? kv.first.Scalar() : "";
      if (!valid_name(name)) {
        error(kv.first, "", "robots",
              "robot names are letters, digits and '_', got " + describe_yaml(kv.first));
        continue;
      }
      if (!kv.second.IsScalar() || kv.second.Scalar().empty()) {
        error(kv.second, "", "robots." + name,
              "expected a robot description file, got " + describe_yaml(kv.second));
        continue;
      }
      fs::path file = kv.second.Scalar();
      if (file.is_relative()) file = exp_.base_dir / file;
      file = file.lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) {
        error(
            kv.second, "", "robots." + name,
            "robot description file '" + file.string() + "' " +
                (fs::exists(file, ec) ? input_file_problem(file) : std::string("does not exist")));
        continue;
      }
      exp_.robots.push_back({name, file, locs_.of(kv.second)});
    }
  }

  // Names that become file names in the run folder (NODE.PORT.csv, runs/NAME).
  static bool safe_file_name(const std::string& name) {
    return !name.empty() && name.size() <= 128 && name[0] != '-' &&
           std::all_of(name.begin(), name.end(), [](char c) {
             return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
           });
  }

  static bool valid_name(const std::string& name) {
    return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
  }

  // --- nodes -----------------------------------------------------------------------------
  void read_nodes(const YAML::Node& root) {
    const YAML::Node nodes = root["nodes"];
    if (!nodes) {
      error(root, "", "nodes", "missing required key (expected a map of node names to nodes)");
      return;
    }
    if (!nodes.IsMap()) {
      error(nodes, "", "nodes",
            "expected a map of node names to nodes, got " + describe_yaml(nodes));
      return;
    }
    std::map<std::string, SourceLocation> seen;
    for (const auto& kv : nodes) {
      const std::string name = kv.first.as<std::string>();
      if (auto it = seen.find(name); it != seen.end()) {
        error(kv.first, name, "",
              "duplicate node name (first defined at " + it->second.str() + ")");
        continue;
      }
      seen[name] = locs_.of(kv.first);
      if (name == "harness" || !safe_file_name(name)) {
        error(kv.first, name, "",
              "invalid node name (letters, digits, '_' and '-'; 'harness' is reserved)");
        continue;
      }
      read_node(name, kv.first, kv.second);
    }
  }

  void read_node(const std::string& name, const YAML::Node& key_node, const YAML::Node& node) {
    NodeSpec ns;
    ns.name = name;
    ns.where = locs_.of(key_node);
    if (!node.IsMap()) {
      error(node, name, "",
            "expected a map with 'plugin', 'params', 'inputs', got " + describe_yaml(node));
      exp_.nodes.push_back(std::move(ns));  // kept (without a spec) so wires to it say no more
      return;
    }
    for (const auto& kv : node) {
      const std::string key = kv.first.as<std::string>();
      if (std::find(kNodeKeys.begin(), kNodeKeys.end(), key) == kNodeKeys.end())
        error(kv.first, name, key,
              "unknown key" + did_you_mean(key, kNodeKeys) +
                  "; expected one of: " + join_names(kNodeKeys));
    }
    const YAML::Node plugin = node["plugin"];
    if (!plugin) {
      error(key_node, name, "plugin", "missing required key (expected a plugin name)");
    } else if (!plugin.IsScalar()) {
      error(plugin, name, "plugin", "expected a plugin name, got " + describe_yaml(plugin));
    } else {
      ns.plugin = plugin.Scalar();
      ns.spec = registry_.find(ns.plugin);
      if (!ns.spec)
        error(plugin, name, "plugin",
              "unknown plugin '" + ns.plugin + "'" + did_you_mean(ns.plugin, registry_.names()) +
                  "; " + registry_.search_report());
    }
    ns.rate_hz = exp_.base_rate_hz;
    if (const YAML::Node r = node["rate_hz"]; r) {
      const auto v = r.IsScalar() ? detail::parse_double(r.Scalar()) : std::nullopt;
      if (!v || !std::isfinite(*v) || *v <= 0)
        error(r, name, "rate_hz", "expected a finite number > 0 [Hz], got " + describe_yaml(r));
      else
        ns.rate_hz = *v;
    }
    const double ratio = exp_.base_rate_hz / ns.rate_hz;
    ns.period_ticks = to_integer<int>(ratio).value_or(0);
    if (ns.period_ticks < 1 || std::abs(ratio - ns.period_ticks) > 1e-9 * ratio)
      error(node["rate_hz"], name, "rate_hz",
            fmt::format("rate {} Hz does not divide the base rate {} Hz (base_rate_hz / rate_hz "
                        "must be a whole number >= 1)",
                        ns.rate_hz, exp_.base_rate_hz));
    if (ns.spec) read_params(ns, node);
    read_inputs(ns, node);
    exp_.nodes.push_back(std::move(ns));
  }

  void read_params(NodeSpec& ns, const YAML::Node& node) {
    const PluginSpec& spec = *ns.spec;
    const YAML::Node params = node["params"];
    std::map<std::string, ParamValue> values;
    if (params && !params.IsMap() && !params.IsNull()) {
      error(params, ns.name, "params",
            "expected a map of parameter names to values, got " + describe_yaml(params));
    } else if (params && params.IsMap()) {
      for (const auto& kv : params) {
        const std::string key = kv.first.as<std::string>();
        const ParamSpec* ps = spec.find_param(key);
        if (!ps) {
          const auto names = spec.param_names();
          error(kv.first, ns.name, "params." + key,
                "unknown parameter of plugin '" + spec.name() + "'" + did_you_mean(key, names) +
                    "; expected one of: " + join_names(names));
          continue;
        }
        std::string problem;
        if (auto v = detail::to_param_value(kv.second, *ps, problem)) {
          values[key] = *v;
          ns.param_locations[key] = locs_.of(kv.second);
        } else {
          error(kv.second, ns.name, "params." + key, problem);
        }
      }
    }
    for (const auto& ps : spec.params()) {
      if (values.count(ps.name)) continue;
      if (ps.default_value)
        values[ps.name] = *ps.default_value;
      else if (!params || params.IsNull() || (params.IsMap() && !params[ps.name]))
        error(params && params.IsMap() ? params : node, ns.name, "params." + ps.name,
              "missing required parameter of plugin '" + spec.name() + "' (expected " +
                  detail::expectation(ps) + (ps.doc.empty() ? "" : ": " + ps.doc) + ")");
    }
    ns.params = Params(std::move(values));
  }

  void read_inputs(NodeSpec& ns, const YAML::Node& node) {
    const YAML::Node inputs = node["inputs"];
    if (!inputs || inputs.IsNull()) return;
    if (!inputs.IsMap()) {
      error(inputs, ns.name, "inputs",
            "expected a map of input ports to 'node.port', got " + describe_yaml(inputs));
      return;
    }
    for (const auto& kv : inputs) {
      InputWire w;
      w.port = kv.first.as<std::string>();
      w.where = locs_.of(kv.second);
      const std::string key = "inputs." + w.port;
      YAML::Node from = kv.second;
      if (kv.second.IsMap()) {
        for (const auto& wk : kv.second) {
          const std::string k = wk.first.as<std::string>();
          if (std::find(kWireKeys.begin(), kWireKeys.end(), k) == kWireKeys.end())
            error(wk.first, ns.name, key + "." + k,
                  "unknown key" + did_you_mean(k, kWireKeys) + "; expected one of: from, delayed");
        }
        if (const YAML::Node d = kv.second["delayed"]; d) {
          const auto b = d.IsScalar() ? detail::parse_bool(d.Scalar()) : std::nullopt;
          if (!b)
            error(d, ns.name, key + ".delayed",
                  "expected a boolean (true/false), got " + describe_yaml(d));
          else
            w.delayed = *b;
        }
        // (a missing key of a const map is an invalid node: test it before reset())
        const YAML::Node f = kv.second["from"];
        if (!f) {
          error(kv.second, ns.name, key, "missing 'from: node.port'");
          continue;
        }
        from.reset(f);
      }
      const std::string text = from.IsScalar() ? from.Scalar() : "";
      const auto dot = text.find('.');
      if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) {
        error(
            from, ns.name, key,
            "expected 'node.port' or {from: node.port, delayed: true}, got " + describe_yaml(from));
        continue;
      }
      w.from_node = text.substr(0, dot);
      w.from_port = text.substr(dot + 1);
      ns.inputs.push_back(std::move(w));
    }
  }

  void read_records(const YAML::Node& root) {
    const YAML::Node rec = root["record"];
    if (!rec || rec.IsNull()) return;
    if (!rec.IsSequence()) {
      error(rec, "", "record", "expected a list of 'node.port', got " + describe_yaml(rec));
      return;
    }
    for (const auto& item : rec) {
      RecordAs as = RecordAs::kFiles;
      YAML::Node port = item;
      if (item.IsMap()) {
        for (const auto& kv : item) {
          const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : "";
          if (k != "port" && k != "as")
            error(kv.first, "", "record." + k,
                  "unknown key" + did_you_mean(k, {"port", "as"}) + "; expected one of: port, as");
        }
        if (const YAML::Node a = item["as"]; a) {
          const std::string value = a.IsScalar() ? a.Scalar() : "";
          if (value == "video")
            as = RecordAs::kVideo;
          else if (value != "files")
            error(a, "", "record.as", "expected one of: files, video; got " + describe_yaml(a));
        }
        // (a missing key of a const map is an invalid node: test it before reset())
        const YAML::Node p = item["port"];
        if (!p) {
          error(item, "", "record", "missing 'port: node.port'");
          continue;
        }
        port.reset(p);
      }
      const std::string text = port.IsScalar() ? port.Scalar() : "";
      const auto dot = text.find('.');
      if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) {
        error(port, "", "record",
              "expected 'node.port' or {port: node.port, as: video}, got " + describe_yaml(port));
        continue;
      }
      exp_.records.push_back({text.substr(0, dot), text.substr(dot + 1), locs_.of(port), as});
    }
  }

  LocationMap locs_;
  PluginRegistry& registry_;
  const LoadOptions& options_;
  Diagnostics diags_;
  std::set<std::pair<std::size_t, int>> visited_;  // containers seen by check_keys
  bool bad_keys_ = false;
  Experiment exp_;
};

}  // namespace

Experiment load_experiment_text(const std::string& yaml, const std::string& display_name,
                                const fs::path& base_dir, PluginRegistry& registry,
                                const LoadOptions& options) {
  return Loader(display_name, base_dir, registry, options).load(yaml);
}

Experiment load_experiment_file(const fs::path& file, PluginRegistry& registry,
                                const LoadOptions& options) {
  std::error_code ec;
  if (!fs::exists(file, ec))
    throw InputError("experiment file '" + file.string() + "' does not exist");
  if (fs::is_directory(file, ec))
    throw InputError("experiment file '" + file.string() + "' is a directory, not a YAML file");
  // Never opened unless a regular file: opening a FIFO blocks, a device never ends.
  if (!fs::is_regular_file(fs::status(file, ec)))
    throw InputError("experiment file '" + file.string() + "' " + input_file_problem(file));
  if (const auto size = fs::file_size(file, ec); !ec && size > kMaxExperimentFileBytes)
    throw InputError(fmt::format("experiment file '{}' is {} bytes; at most {} (2 MiB) are read",
                                 file.string(), size, kMaxExperimentFileBytes));
  std::ifstream in(file);
  if (!in) throw InputError("experiment file '" + file.string() + "' cannot be read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (buffer.str().find('\0') != std::string::npos)
    throw InputError("experiment file '" + file.string() +
                     "' is binary (it holds NUL bytes), not a YAML text file");
  const fs::path dir = fs::absolute(file).parent_path().lexically_normal();
  return load_experiment_text(buffer.str(), file.string(), dir, registry, options);
}

const NodeSpec* Experiment::find_node(const std::string& node_name) const {
  for (const auto& n : nodes)
    if (n.name == node_name) return &n;
  return nullptr;
}

const RobotSpec* Experiment::find_robot(const std::string& robot_name) const {
  for (const auto& r : robots)
    if (r.name == robot_name) return &r;
  return nullptr;
}

}  // namespace somasim
