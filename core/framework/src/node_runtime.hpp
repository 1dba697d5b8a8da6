#pragma once
// Internal: the framework's per-node state behind NodeContext.
#include <map>
#include <memory>
#include <random>
#include <string>

#include <spdlog/logger.h>

#include "somasim/experiment.hpp"
#include "somasim/plugin.hpp"

namespace somasim {

class Simulation;

class NodeRuntime {
 public:
  NodeRuntime(Simulation& sim, const NodeSpec& spec, std::shared_ptr<spdlog::logger> log);

  Simulation& sim;
  const NodeSpec& spec;
  std::unique_ptr<Plugin> plugin;
  NodeContext context;
  std::mt19937_64 rng;
  std::shared_ptr<spdlog::logger> log;
  std::map<std::string, std::shared_ptr<void>> outputs;  // owned storage
  std::map<std::string, void*> inputs;                   // producer storage or delay buffer
  std::vector<std::pair<std::string, nlohmann::json>> metrics;
  std::int64_t next_tick = 0;                          // the base tick of this node's next step
  std::int64_t last_step_tick = -1;                    // the base tick of its last step
  std::vector<PortRecorder*> recorders;                // recorders of this node's outputs
  std::int64_t progress_done = 0, progress_total = 0;  // NodeContext::report_progress
  std::string progress_what;
};

}  // namespace somasim
