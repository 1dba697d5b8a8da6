// Reading a sweep file: its own keys, checked and located (the runs themselves are checked by
// the experiment loader, in jobs.cpp).
#include "somasim/sweep/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/numeric.hpp"
#include "somasim/yaml_text.hpp"
#include "yaml_value_text.hpp"

namespace somasim::sweep {
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kTopKeys = {"sweep", "description", "experiment", "output", "seeds",
                                           "mode",  "set",         "axes",       "summary"};
const std::vector<std::string> kRangeKeys = {"from", "to", "step", "count"};
const std::vector<std::string> kSeedRangeKeys = {"from", "to"};
const std::vector<std::string> kSummaryKeys = {"metric", "against"};
// A sweep file is a few dozen lines; this bounds the parser's memory (~200x the file).
constexpr std::uintmax_t kMaxSweepFileBytes = 1u << 20;
// More runs than any cluster allocation would take; bounds memory against a typo'd step.
constexpr std::size_t kMaxValues = 100000;        // of one axis
constexpr std::size_t kMaxTotalValues = 1000000;  // of all axes together

bool safe_name(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

bool valid_path(const std::string& path) {
  if (path.empty() || path.front() == '.' || path.back() == '.') return false;
  return path.find("..") == std::string::npos && path.find_first_of(" \t=") == std::string::npos;
}

class SweepReader {
 public:
  SweepReader(std::string display, fs::path base_dir)
      : display_(std::move(display)), base_dir_(std::move(base_dir)) {
    spec_.file = display_;
  }

  SweepSpec read(const std::string& text) {
    YAML::Node root;
    try {
      root = load_one_document(text);
    } catch (const YAML::ParserException& e) {
      throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", display_, e.mark.line + 1,
                                   e.mark.column + 1, e.msg));
    } catch (const InputError& e) {
      throw InputError(display_ + ": " + e.what());
    }
    if (!root.IsMap())
      throw InputError(loc(root).str() +
                       ": expected a map with the keys 'sweep', 'experiment' and 'axes', got " +
                       describe_yaml(root));
    if (!check_keys(root, kTopKeys, "")) diags_.throw_if_any();
    spec_.name = read_string(root, "sweep", true);
    if (!spec_.name.empty() && !safe_name(spec_.name))
      error(root["sweep"], "sweep",
            "expected a name of letters, digits, '_' and '-', got " + describe_yaml(root["sweep"]));
    if (root["description"]) read_string(root, "description", false);
    read_experiment(root);
    if (root["output"]) spec_.output = read_string(root, "output", false);
    read_seeds(root["seeds"]);
    read_mode(root["mode"]);
    read_fixed(root["set"]);
    read_axes(root["axes"], root);
    check_runs_distinct();
    read_summary(root["summary"]);
    diags_.throw_if_any();
    return std::move(spec_);
  }

 private:
  SourceLocation loc(const YAML::Node& n) const {
    const YAML::Mark m = n.Mark();
    if (m.is_null()) return {display_, 0, 0};
    return {display_, m.line + 1, m.column + 1};
  }
  void error(const YAML::Node& at, const std::string& key, const std::string& msg) {
    diags_.add(loc(at), "", key, msg);
  }

  // Unknown and duplicate keys, and keys that are not names. False when a key is not a scalar.
  bool check_keys(const YAML::Node& map, const std::vector<std::string>& allowed,
                  const std::string& prefix) {
    std::map<std::string, SourceLocation> seen;
    bool ok = true;
    for (const auto& kv : map) {
      if (!kv.first.IsScalar()) {
        error(kv.first, prefix.empty() ? "(top level)" : prefix,
              "keys must be plain names, got " + describe_yaml(kv.first) + " as a key");
        ok = false;
        continue;
      }
      const std::string key = kv.first.Scalar();
      const std::string shown = prefix.empty() ? key : prefix + "." + key;
      if (auto it = seen.find(key); it != seen.end()) {
        error(kv.first, shown, "duplicate key (first defined at " + it->second.str() + ")");
        continue;
      }
      seen[key] = loc(kv.first);
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        error(kv.first, shown,
              "unknown key" + did_you_mean(key, allowed) +
                  "; expected one of: " + join_names(allowed));
    }
    return ok;
  }

  std::string read_string(const YAML::Node& map, const std::string& key, bool required) {
    const YAML::Node n = map[key];
    if (!n) {
      if (required) error(map, key, "missing required key (expected a string)");
      return {};
    }
    if (!n.IsScalar() || n.Scalar().empty()) {
      error(n, key, "expected a string, got " + describe_yaml(n));
      return {};
    }
    return n.Scalar();
  }

  void read_experiment(const YAML::Node& root) {
    const std::string given = read_string(root, "experiment", true);
    if (given.empty()) return;
    spec_.experiment_where = loc(root["experiment"]);
    fs::path p = given;
    if (p.is_relative()) p = base_dir_ / p;
    spec_.experiment = fs::absolute(p).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(spec_.experiment, ec))
      error(root["experiment"], "experiment",
            "expected an experiment file (relative to the sweep file), but '" +
                spec_.experiment.string() + "' " +
                (fs::exists(spec_.experiment, ec) ? "is not a file" : "does not exist"));
  }

  std::optional<double> number(const YAML::Node& n) {
    if (!n.IsScalar()) return std::nullopt;
    const auto v = parse_double(n.Scalar());
    if (!v || !std::isfinite(*v)) return std::nullopt;
    return v;
  }

  static bool seed_at(const YAML::Node& n, std::uint64_t& out) {
    if (!n || !n.IsScalar()) return false;
    const auto v = parse_seed(n.Scalar());
    if (v) out = *v;
    return v.has_value();
  }
  bool number_at(const YAML::Node& n, double& out) {
    if (!n) return false;
    const auto v = number(n);
    if (v) out = *v;
    return v.has_value();
  }

  void read_seeds(const YAML::Node& n) {
    if (!n) return;
    const std::string expect = std::string("expected a list of seeds (each ") + kSeedExpectation +
                               ") or a range {from: A, to: B}, got ";
    if (n.IsMap()) {
      if (!check_keys(n, kSeedRangeKeys, "seeds")) return;
      // (plain values, not optionals: GCC 12 warns falsely on them here, -Wmaybe-uninitialized)
      std::uint64_t from_v = 0, to_v = 0;
      const bool ok = seed_at(n["from"], from_v) && seed_at(n["to"], to_v);
      if (!ok) {
        error(n, "seeds",
              std::string("a seed range needs 'from' and 'to', each ") + kSeedExpectation);
        return;
      }
      const std::uint64_t* from = &from_v;
      const std::uint64_t* to = &to_v;
      if (*to < *from) {
        error(n, "seeds", fmt::format("expected 'to' >= 'from', got from {} to {}", *from, *to));
        return;
      }
      if (*to - *from >= kMaxValues) {
        error(n, "seeds", fmt::format("at most {} seeds, got {} to {}", kMaxValues, *from, *to));
        return;
      }
      for (std::uint64_t s = *from;; ++s) {
        spec_.seeds.push_back(s);
        if (s == *to) break;
      }
      return;
    }
    if (!n.IsSequence()) {
      error(n, "seeds", expect + describe_yaml(n));
      return;
    }
    if (n.size() == 0) {
      error(n, "seeds", "expected at least one seed, got an empty list");
      return;
    }
    std::map<std::uint64_t, SourceLocation> seen;
    for (const auto& item : n) {
      const auto seed = item.IsScalar() ? parse_seed(item.Scalar()) : std::nullopt;
      if (!seed) {
        error(
            item, "seeds",
            std::string("expected a seed (") + kSeedExpectation + "), got " + describe_yaml(item));
        continue;
      }
      if (auto it = seen.find(*seed); it != seen.end()) {
        error(item, "seeds",
              fmt::format("seed {} is listed twice (first at {}); two runs would be identical",
                          *seed, it->second.str()));
        continue;
      }
      seen[*seed] = loc(item);
      spec_.seeds.push_back(*seed);
    }
  }

  void read_mode(const YAML::Node& n) {
    if (!n) return;
    if (n.IsScalar() && n.Scalar() == "grid") return;
    if (n.IsScalar() && n.Scalar() == "zip") {
      spec_.mode = SweepMode::kZip;
      return;
    }
    error(n, "mode", "expected 'grid' or 'zip', got " + describe_yaml(n));
  }

  bool read_path_key(const YAML::Node& key, const std::string& section) {
    if (valid_path(key.Scalar())) return true;
    error(key, section + "." + key.Scalar(),
          "expected a dotted --set path such as nodes.NODE.params.NAME");
    return false;
  }

  void read_fixed(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsMap()) {
      error(n, "set", "expected a map of PATH: VALUE, got " + describe_yaml(n));
      return;
    }
    if (!check_keys(n, {}, "set")) return;
    for (const auto& kv : n) {
      if (!read_path_key(kv.first, "set")) continue;
      Axis a;
      a.path = kv.first.Scalar();
      a.where = loc(kv.first);
      if (!kv.second.IsDefined() || kv.second.IsNull()) {
        error(kv.second, "set." + a.path, "expected a value, got nothing");
        continue;
      }
      a.values.push_back({yaml_value_text(kv.second), loc(kv.second)});
      spec_.fixed.push_back(std::move(a));
    }
  }

  void read_axes(const YAML::Node& n, const YAML::Node& root) {
    if (!n) {
      // A seed soak: the experiment as it is, once per seed.
      if (!spec_.seeds.empty()) return;
      error(root, "axes",
            "missing required key (expected a map of PATH: values; a sweep without axes needs "
            "'seeds')");
      return;
    }
    if (!n.IsMap() || n.size() == 0) {
      error(n, "axes",
            "expected a map of PATH: values (at least one axis), got " + describe_yaml(n));
      return;
    }
    if (!check_keys(n, {}, "axes")) return;
    std::set<std::string> seen;
    for (const auto& kv : n) {
      if (!read_path_key(kv.first, "axes") || !seen.insert(kv.first.Scalar()).second) continue;
      Axis a;
      a.path = kv.first.Scalar();
      a.where = loc(kv.first);
      const std::string key = "axes." + a.path;
      for (const auto& f : spec_.fixed)
        if (f.path == a.path)
          error(kv.first, key, "is also fixed in 'set' (at " + f.where.str() + "); keep one");
      if (a.path == "seed" && root["seeds"])
        error(kv.first, key,
              "is also swept by 'seeds' (at " + loc(root["seeds"]).str() +
                  "), which would override it in every run; keep one");
      const YAML::Node v = kv.second;
      if (v.IsSequence()) {
        if (v.size() == 0) error(v, key, "expected at least one value, got an empty list");
        for (const auto& item : v) {
          if (item.IsNull())
            error(item, key, "expected a value, got nothing");
          else
            a.values.push_back({yaml_value_text(item), loc(item)});
        }
      } else if (v.IsMap()) {
        read_range(v, key, a);
      } else {
        error(v, key,
              "expected a list of values or a range {from, to, step} or {from, to, count}, got " +
                  describe_yaml(v));
      }
      total_values_ += a.values.size();
      spec_.axes.push_back(std::move(a));
    }
  }

  // Values that are the same value (0.0 and -0.0, 1 and 1.0, a text twice) would make
  // identical runs: in grid mode two values of one axis, in zip mode two positions whose values
  // agree on every axis. Compared by a canonical key (numbers by value), in linear time.
  static std::string value_key(const AxisValue& v) {
    // Integers beyond 2^53 are told apart exactly (a double would merge neighbours).
    if (const auto i = exact_integer(v.text); i && (*i > kExactInDouble || *i < -kExactInDouble))
      return *i < 0 ? fmt::format("i-{}", static_cast<unsigned long long>(-*i))
                    : fmt::format("i{}", static_cast<unsigned long long>(*i));
    if (const auto x = parse_double(v.text)) return fmt::format("n{:.17g}", *x + 0.0);  // -0 = 0
    return "t" + v.text;
  }
  static constexpr __int128 kExactInDouble = __int128{1} << 53;
  // A decimal integer of at most 64 bits' magnitude (optional sign; no fraction, no exponent).
  static std::optional<__int128> exact_integer(const std::string& text) {
    std::size_t at = text.size() > 1 && (text[0] == '-' || text[0] == '+') ? 1 : 0;
    if (at == text.size() || text.size() - at > 20) return std::nullopt;
    __int128 value = 0;
    for (std::size_t k = at; k < text.size(); ++k) {
      if (text[k] < '0' || text[k] > '9') return std::nullopt;
      value = value * 10 + (text[k] - '0');
    }
    if (value > static_cast<__int128>(UINT64_MAX)) return std::nullopt;
    return text[0] == '-' ? -value : value;
  }

  void check_runs_distinct() {
    const auto duplicate = [&](const std::vector<std::string>& keys)
        -> std::optional<std::pair<std::size_t, std::size_t>> {
      std::unordered_map<std::string, std::size_t> first;
      for (std::size_t i = 0; i < keys.size(); ++i)
        if (const auto [it, fresh] = first.emplace(keys[i], i); !fresh)
          return std::make_pair(it->second, i);
      return std::nullopt;
    };
    if (spec_.mode == SweepMode::kGrid) {
      for (const Axis& a : spec_.axes) {
        std::vector<std::string> keys;
        for (const AxisValue& v : a.values) keys.push_back(value_key(v));
        if (const auto d = duplicate(keys)) {
          const AxisValue &x = a.values[d->second], &y = a.values[d->first];
          diags_.add(x.where, "", "axes." + a.path,
                     fmt::format("value {} is the same as {} (at {}); two runs would be identical",
                                 x.text, y.text, y.where.str()));
          return;
        }
      }
      return;
    }
    if (spec_.axes.empty()) return;
    std::size_t n = spec_.axes.front().values.size();
    for (const Axis& a : spec_.axes) n = std::min(n, a.values.size());
    std::vector<std::string> keys(n);
    for (const Axis& a : spec_.axes)
      for (std::size_t i = 0; i < n; ++i) keys[i] += value_key(a.values[i]) + '\x1f';
    if (const auto d = duplicate(keys))
      diags_.add(spec_.axes.front().values[d->second].where, "", "axes",
                 fmt::format("zip position {} has the same values as position {} on every axis; "
                             "two runs would be identical",
                             d->second + 1, d->first + 1));
  }

  void read_range(const YAML::Node& v, const std::string& key, Axis& a) {
    const std::size_t before = diags_.total();
    if (!check_keys(v, kRangeKeys, key) || diags_.total() > before) return;
    double from_v = 0, to_v = 0;  // (not optionals: see read_seeds)
    const bool ends = number_at(v["from"], from_v) && number_at(v["to"], to_v);
    const bool has_step = static_cast<bool>(v["step"]);
    const bool has_count = static_cast<bool>(v["count"]);
    if (!ends || has_step == has_count) {
      error(v, key,
            "a range needs finite numbers 'from' and 'to' and one of 'step' (> 0) or 'count' (an "
            "integer >= 1)");
      return;
    }
    const double* from = &from_v;
    const double* to = &to_v;
    std::vector<double> values;
    bool integers = false;
    if (has_step) {
      const auto step = number(v["step"]);
      if (!step || *step <= 0) {
        error(v["step"], key, "expected 'step' > 0, got " + describe_yaml(v["step"]));
        return;
      }
      const double n = std::floor(std::abs(*to - *from) / *step + 1e-9);
      if (n + 1 > static_cast<double>(kMaxValues)) {
        error(v, key, fmt::format("the range has more than {} values", kMaxValues));
        return;
      }
      if (n + 1 + static_cast<double>(total_values_) > static_cast<double>(kMaxTotalValues)) {
        error(v, key, fmt::format("the axes hold more than {} values in all", kMaxTotalValues));
        return;
      }
      const double dir = *to >= *from ? 1.0 : -1.0;
      for (int i = 0; i <= static_cast<int>(n); ++i) values.push_back(*from + dir * i * *step);
      integers = parse_int(v["from"].Scalar()) && parse_int(v["to"].Scalar()) &&
                 parse_int(v["step"].Scalar());
    } else {
      const auto count = v["count"].IsScalar() ? parse_int(v["count"].Scalar()) : std::nullopt;
      if (count && *count >= 1 &&
          static_cast<std::size_t>(*count) + total_values_ > kMaxTotalValues) {
        error(v, key, fmt::format("the axes hold more than {} values in all", kMaxTotalValues));
        return;
      }
      if (!count || *count < 1 || *count > static_cast<std::int64_t>(kMaxValues)) {
        error(v["count"], key,
              fmt::format("expected 'count' an integer in [1, {}], got {}", kMaxValues,
                          describe_yaml(v["count"])));
        return;
      }
      for (std::int64_t i = 0; i < *count; ++i)
        values.push_back(*count == 1 ? *from
                                     : *from + (*to - *from) * static_cast<double>(i) /
                                                   static_cast<double>(*count - 1));
    }
    // Values as 12 significant digits, and 0 for what is zero but for rounding: from + i * step
    // accumulates binary rounding (-0.15 + 0.05 * 1 = -0.09999999999999999), which would reach
    // the run folders, the manifests and sweep.csv.
    const double scale = std::max(std::abs(*from), std::abs(*to));
    for (double x : values) {
      if (std::abs(x) < 1e-12 * scale) x = 0.0;
      const std::optional<std::int64_t> whole = to_integer<std::int64_t>(x);
      a.values.push_back(
          {integers && whole ? fmt::format("{}", *whole) : fmt::format("{:.12g}", x), loc(v)});
    }
  }

  void read_summary(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsMap()) {
      error(n, "summary", "expected a map {metric: KEY, against: AXIS}, got " + describe_yaml(n));
      return;
    }
    if (!check_keys(n, kSummaryKeys, "summary")) return;
    spec_.summary_metric = read_string(n, "metric", true);
    if (n["against"]) {
      spec_.summary_against = read_string(n, "against", false);
    } else if (spec_.axes.size() == 1) {
      spec_.summary_against = spec_.axes.front().path;
    } else {
      error(n, "summary",
            "missing key 'against' (expected one of the axes: " + join_names(axis_paths()) + ")");
      return;
    }
    if (spec_.summary_against.empty()) return;
    const auto paths = axis_paths();
    if (!paths.empty() &&
        std::find(paths.begin(), paths.end(), spec_.summary_against) == paths.end())
      error(n["against"], "summary.against",
            "'" + spec_.summary_against + "' is not an axis" +
                did_you_mean(spec_.summary_against, paths) +
                "; expected one of: " + join_names(paths));
  }

  std::vector<std::string> axis_paths() const {
    std::vector<std::string> out;
    for (const auto& a : spec_.axes) out.push_back(a.path);
    return out;
  }

  std::string display_;
  fs::path base_dir_;
  std::size_t total_values_ = 0;  // over the axes read so far
  SweepSpec spec_;
  Diagnostics diags_;
};

}  // namespace

SweepSpec load_sweep_text(const std::string& yaml, const std::string& display_name,
                          const fs::path& base_dir) {
  return SweepReader(display_name, base_dir).read(yaml);
}

SweepSpec load_sweep_file(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError("sweep file '" + file.string() + "' " +
                     (fs::exists(file, ec) ? "is not a file" : "does not exist"));
  if (const auto size = fs::file_size(file, ec); !ec && size > kMaxSweepFileBytes)
    throw InputError(fmt::format("sweep file '{}' is {} bytes; at most {} (1 MiB) are read",
                                 file.string(), size, kMaxSweepFileBytes));
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (!in) throw InputError("sweep file '" + file.string() + "' cannot be read");
  if (buffer.str().find('\0') != std::string::npos)
    throw InputError("sweep file '" + file.string() + "' is binary (it holds NUL bytes)");
  return load_sweep_text(buffer.str(), file.string(),
                         fs::absolute(file).parent_path().lexically_normal());
}

fs::path output_root(const SweepSpec& spec, const std::string& cli_out) {
  if (!cli_out.empty()) return cli_out;
  if (spec.output) return *spec.output;
  return fs::path("runs") / "sweeps" / spec.name;
}

}  // namespace somasim::sweep
