#pragma once
/// @file
/// The scheduler: an instantiated experiment stepped on simulated time.
///
/// One base tick of 1/base_rate_hz seconds; node i steps at ticks k with
/// k % period_ticks(i) == 0, in the topological order of its inputs. Delayed inputs read the
/// producer's value at the end of the previous base tick. Nothing here depends on wall time
/// or thread count, so the same experiment and seed give the same results. A delayed input is
/// copied (PortTypeInfo::copy) only at the end of the ticks its producer stepped in: outputs
/// change only in step(), so the value read is the same and slow producers cost nothing.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/logger.h>
#include <nlohmann/json.hpp>

#include "somasim/experiment.hpp"
#include "somasim/plugin.hpp"

namespace somasim {

class NodeRuntime;

class Simulation {
 public:
  /// `out_dir` receives figures, CSVs and other artefacts; `logger` gets the run log.
  Simulation(const Experiment& experiment, std::filesystem::path out_dir,
             std::shared_ptr<spdlog::logger> logger);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Instantiates plugins, allocates ports and configures every node (InputError on bad input).
  void configure();
  /// Opens recorders and calls start() on every node.
  void start();
  /// Runs one base tick. Returns false once the run is over (duration reached or a stop was
  /// requested) — then no tick was run.
  bool step();
  /// Calls finish() on every node; an exception in one node does not stop the others. Returns
  /// the first error message, if any.
  std::string finish();

  double time_s() const;  ///< sim time of the next tick [s]
  std::int64_t tick() const { return tick_; }
  std::int64_t total_ticks() const { return total_ticks_; }
  const std::string& stop_reason() const { return stop_reason_; }
  const Experiment& experiment() const { return exp_; }
  /// A node's report of how far it is towards ending the run (NodeContext::report_progress).
  struct NodeProgress {
    std::string node, what;
    std::int64_t done = 0, total = 0;
  };
  /// The node report furthest towards its total (nullopt when no node reports progress).
  std::optional<NodeProgress> furthest_progress() const;
  /// How far the run is, in [0, 1]: the larger of simulated time over duration and the
  /// furthest node's done / total.
  double progress_fraction() const;
  /// Metrics reported by nodes: node name → {metric → value}.
  const nlohmann::ordered_json& node_metrics() const { return metrics_; }
  /// The node that was stepping when step() threw (for messages).
  const std::string& current_node() const { return current_node_; }

  /// Whether `port` of `node` is read: an input of another node is wired to it, a recorder
  /// records it, or every output counts as read (set_all_outputs_read: the test harness, which
  /// may read any output).
  bool output_read(const std::string& node, const std::string& port) const;
  /// Makes every output count as read (call before configure()).
  void set_all_outputs_read(bool all) { all_outputs_read_ = all; }

  /// Test harness: the storage behind inputs wired to "harness.NAME".
  void* harness_port(const std::string& name, const std::string& type_name);
  /// Any node's output storage (test harness and tools).
  void* output_port(const std::string& node, const std::string& port, const std::string& type_name);

 private:
  friend class NodeRuntime;
  friend class NodeContext;
  void copy_delayed();

  const Experiment& exp_;
  std::filesystem::path out_dir_;
  std::shared_ptr<spdlog::logger> logger_;
  std::vector<std::unique_ptr<NodeRuntime>> nodes_;  // in exp_.nodes order
  std::vector<NodeRuntime*> ordered_;                // in exp_.order (step order)
  struct DelayedEdge {
    const PortTypeInfo* type;
    const NodeRuntime* producer_node;  // copied only at the end of a tick it stepped in
    void* producer;
    std::shared_ptr<void> buffer;
  };
  std::vector<DelayedEdge> delayed_;
  struct HarnessPort {
    std::string name;
    const PortTypeInfo* type;
    std::shared_ptr<void> storage;
  };
  std::vector<HarnessPort> harness_ports_;
  std::vector<std::unique_ptr<PortRecorder>> recorders_;
  std::map<std::string, std::shared_ptr<const void>> run_shared_;  // NodeContext::run_shared
  // Output files named by parameters: run-folder-relative file -> "node 'n', key 'k'".
  std::map<std::string, std::string> claimed_outputs_;
  nlohmann::ordered_json metrics_ = nlohmann::ordered_json::object();
  std::int64_t tick_ = 0;
  std::int64_t total_ticks_ = 0;
  std::string stop_reason_;
  std::string current_node_;
  bool configured_ = false;
  bool all_outputs_read_ = false;
};

}  // namespace somasim
