// sweep.csv: every run's metrics in one table.
#include "somasim/sweep/collect.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "somasim/metrics_layout.hpp"
#include "somasim/sweep/run_folder.hpp"

namespace somasim::sweep {
namespace fs = std::filesystem;

namespace {

// Columns the table already has, and metrics.json entries that are not per-run figures.
const std::set<std::string> kSkippedMetrics = {"status", "seed", "experiment", "pid", "host"};

std::optional<nlohmann::json> read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// A metric as a cell; nullopt for values that are not one figure (lists, maps).
std::optional<std::string> cell(const nlohmann::json& v) {
  if (v.is_null()) return std::string();
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return std::string(v.get<bool>() ? "true" : "false");
  if (v.is_number()) return v.dump();  // shortest text that reads back the same double
  return std::nullopt;
}

std::string quoted(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

bool is_wall_clock_column(const std::string& name) {
  if (name == "wall_time_s" || name == "real_time_factor" || name == "host") return true;
  return name.size() > 3 && name.compare(name.size() - 3, 3, "_ms") == 0;
}

SweepTable collect_table(const fs::path& root) {
  const nlohmann::json manifest = read_sweep_manifest(root);
  SweepTable table;
  for (const auto& a : manifest["axes"]) table.axes.push_back(a.value("path", ""));
  if (manifest.contains("summary")) {
    table.summary_metric = manifest["summary"].value("metric", "");
    table.summary_against = manifest["summary"].value("against", "");
  }
  struct Run {
    std::vector<std::string> fixed;  // index .. status
    std::map<std::string, std::string> metrics;
  };
  std::vector<Run> runs;
  std::set<std::string> keys;
  for (const auto& job : manifest["jobs"]) {
    Run run;
    const std::string folder = job.value("folder", "");
    run.fixed = {std::to_string(job.value("index", 0)), folder,
                 std::to_string(job.value("seed", std::uint64_t{0}))};
    const auto values = job.value("values", std::vector<std::string>{});
    for (std::size_t a = 0; a < table.axes.size(); ++a)
      run.fixed.push_back(a < values.size() ? values[a] : "");
    const auto metrics = read_json(root / folder / "metrics.json");
    run.fixed.push_back(metrics ? metrics->value("status", "unknown") : "missing");
    if (metrics && metrics->is_object())
      for (const auto& [k, v] : flatten_metrics(*metrics)) {
        if (kSkippedMetrics.count(k) || k.starts_with("versions.")) continue;
        if (const auto c = cell(v)) {
          run.metrics[k] = *c;
          keys.insert(k);
        }
      }
    if (const auto m = read_json(root / folder / "manifest.json"); m && m->is_object())
      run.metrics["host"] = m->value("host", "");
    keys.insert("host");
    runs.push_back(std::move(run));
  }
  table.header = {"index", "folder", "seed"};
  table.header.insert(table.header.end(), table.axes.begin(), table.axes.end());
  table.header.push_back("status");
  std::vector<std::string> ordered;
  for (const auto& k : keys)
    if (!is_wall_clock_column(k)) ordered.push_back(k);
  for (const auto& k : keys)
    if (is_wall_clock_column(k)) ordered.push_back(k);
  table.header.insert(table.header.end(), ordered.begin(), ordered.end());
  for (const Run& run : runs) {
    std::vector<std::string> row = run.fixed;
    for (const auto& k : ordered) {
      const auto it = run.metrics.find(k);
      row.push_back(it == run.metrics.end() ? "" : it->second);
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::string table_csv(const SweepTable& table) {
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i > 0) out.push_back(',');
      out.append(quoted(cells[i]));
    }
    out += "\n";
  };
  line(table.header);
  for (const auto& row : table.rows) line(row);
  return out;
}

}  // namespace somasim::sweep
