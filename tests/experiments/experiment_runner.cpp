#include "experiment_runner.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "somasim/metrics_layout.hpp"
#include "somasim/plugin_registry.hpp"

namespace somasim::testing {
namespace fs = std::filesystem;

ExperimentRun run_config(const std::string& name, const std::vector<Override>& overrides,
                         const std::string& tag) {
  PluginRegistry registry(PluginRegistry::default_search_path({}));
  LoadOptions options;
  options.overrides = overrides;
  const Experiment exp = load_experiment_file(
      fs::path(SOMASIM_SOURCE_DIR) / "configs" / (name + ".yaml"), registry, options);
  ExperimentRun run;
  run.dir = fs::temp_directory_path() / ("somasim-exp-" + std::to_string(::getpid()) + "-" + name +
                                         (tag.empty() ? "" : "-" + tag));
  fs::remove_all(run.dir);
  RunOptions ro;
  ro.out_dir = run.dir;
  ro.quiet = true;
  run.report = run_experiment(exp, ro);
  run.metrics = nlohmann::json::parse(read_file(run.dir / "metrics.json"));
  run.flat = nlohmann::json::object();
  for (const auto& [key, value] : run.metrics.items())
    if (key != "nodes") run.flat[key] = value;
  for (const auto& [flat_name, value] : node_metrics_by_flat_name(run.metrics))
    run.flat[flat_name] = value;
  return run;
}

nlohmann::json ExperimentRun::metric(std::string_view name) const {
  return find_metric(metrics, name).value_or(nlohmann::json());
}

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path shared_dir() {
  const char* env = std::getenv("SOMASIM_SHARED_DIR");
  const fs::path dir = env ? fs::path(env) : fs::path(SOMASIM_SOURCE_DIR) / ".." / "shared";
  return fs::is_directory(dir) ? dir : fs::path();
}

}  // namespace somasim::testing
