#include "somasim/testing/harness.hpp"

#include <spdlog/sinks/null_sink.h>
#include <unistd.h>

#include <atomic>

namespace somasim::testing {
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir() {
  static std::atomic<int> counter{0};
  const fs::path dir =
      fs::temp_directory_path() /
      ("somasim-harness-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

LoadOptions harness_options(LoadOptions options) {
  options.allow_harness_inputs = true;
  options.defaults_for_tests = true;
  return options;
}
}  // namespace

Harness::Harness(const std::string& yaml, const std::vector<fs::path>& plugin_path,
                 const LoadOptions& options)
    : registry_(PluginRegistry::default_search_path(plugin_path)),
      experiment_(load_experiment_text(yaml, "<inline>", fs::current_path(), registry_,
                                       harness_options(options))),
      out_dir_(fresh_dir()) {
  auto logger =
      std::make_shared<spdlog::logger>("harness", std::make_shared<spdlog::sinks::null_sink_mt>());
  try {
    sim_ = std::make_unique<Simulation>(experiment_, out_dir_, logger);
    sim_->set_all_outputs_read(true);  // a test may read any output
    sim_->configure();
  } catch (...) {  // no destructor runs: leave no run folder behind
    sim_.reset();
    std::error_code ec;
    fs::remove_all(out_dir_, ec);
    throw;
  }
}

Harness::~Harness() {
  sim_.reset();
  std::error_code ec;
  fs::remove_all(out_dir_, ec);
}

bool Harness::step(int ticks) {
  if (!started_) {
    sim_->start();
    started_ = true;
  }
  for (int i = 0; i < ticks; ++i)
    if (!sim_->step()) return false;
  return true;
}

std::string Harness::finish() {
  if (finished_) return "";
  finished_ = true;
  return sim_->finish();
}

nlohmann::json Harness::metric(const std::string& node, const std::string& name) const {
  const auto& m = sim_->node_metrics();
  if (!m.contains(node) || !m[node].contains(name)) return nullptr;
  return m[node][name];
}

}  // namespace somasim::testing
