#pragma once
/// @file
/// Test a plugin in isolation, from inline YAML:
/// @code
///   somasim::testing::Harness h(R"(
///     nodes:
///       thrower: {plugin: taxel_thrower, params: {throws: 3}}
///       pps:
///         plugin: pps_learner
///         params: {ttc_max: 3}
///         inputs: {stimulus: harness.stim, taxels: thrower.taxels, contacts: thrower.contacts}
///   )");
///   h.input<somasim::pps::Stimulus>("stim").present = true;  // feed an input
///   h.step(10);                                              // ten base ticks
///   const auto& act = h.output<somasim::TaxelValues>("pps.activations");
///   h.finish();
///   const nlohmann::json events = h.metric("pps", "events");
/// @endcode
/// `experiment` and `duration_s` may be omitted; inputs may be wired to "harness.NAME".
/// Plugins are found on the default search path (plus `plugin_path`).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/port_type.hpp"
#include "somasim/simulation.hpp"

namespace somasim::testing {

class Harness {
 public:
  /// Parses, validates and configures the graph (throws InputError like `somasim validate`).
  explicit Harness(const std::string& yaml,
                   const std::vector<std::filesystem::path>& plugin_path = {},
                   const LoadOptions& options = {});
  ~Harness();

  /// The storage behind inputs wired to "harness.NAME"; write it before step().
  template <class T>
  T& input(const std::string& name) {
    void* storage = sim_->harness_port(name, port_type<T>().name);
    if (!storage) throw InputError("no input is wired to 'harness." + name + "'");
    return *static_cast<T*>(storage);
  }
  /// A node's output, "node.port".
  template <class T>
  const T& output(const std::string& node_dot_port) {
    const auto dot = node_dot_port.find('.');
    return *static_cast<const T*>(sim_->output_port(
        node_dot_port.substr(0, dot), node_dot_port.substr(dot + 1), port_type<T>().name));
  }
  /// Runs `ticks` base ticks (start() happens on the first call). Returns false if the run
  /// ended (duration reached or a node requested a stop) before all ticks ran.
  bool step(int ticks = 1);
  /// Calls finish() on all nodes (once); returns the first error, "" if none.
  std::string finish();
  /// A metric reported by `node` (null json if absent). Call after finish().
  nlohmann::json metric(const std::string& node, const std::string& name) const;

  double time_s() const { return sim_->time_s(); }
  const Experiment& experiment() const { return experiment_; }
  /// The run folder (a fresh temporary directory, removed with the harness).
  const std::filesystem::path& out_dir() const { return out_dir_; }

 private:
  PluginRegistry registry_;
  Experiment experiment_;
  std::filesystem::path out_dir_;
  std::unique_ptr<Simulation> sim_;
  bool started_ = false;
  bool finished_ = false;
};

}  // namespace somasim::testing
