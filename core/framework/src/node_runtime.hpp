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
class CsvRecorder;

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
  std::int64_t next_tick = 0;           // the base tick of this node's next step
  std::vector<CsvRecorder*> recorders;  // recorders of this node's outputs
};

/// Writes one recorded port to `<dir>/<node>.<port>.csv`; header on the first row.
class CsvRecorder {
 public:
  CsvRecorder(const std::filesystem::path& file, const PortTypeInfo& type, const void* value);
  void write(double time_s);
  void flush();
  const std::string& node_name() const { return node_; }
  void set_node(std::string n) { node_ = std::move(n); }

 private:
  std::filesystem::path file_;
  const PortTypeInfo& type_;
  const void* value_;
  std::FILE* out_ = nullptr;
  std::string row_;
  std::string node_;
  bool header_written_ = false;
};

}  // namespace somasim
