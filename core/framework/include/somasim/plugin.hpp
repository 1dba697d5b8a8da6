#pragma once
/// @file
/// The plugin interface: configure → start → step(t) → finish, and the context a node sees.
///
/// A plugin library registers its plugins in one `register.cpp`:
/// @code
///   SOMASIM_PLUGIN_LIBRARY(registrar) { registrar.add<MyPlugin>(); }
/// @endcode
/// where `MyPlugin` derives from somasim::Plugin and has `static PluginSpec spec()`.
/// The framework's own port types (double, Eigen::Vector3d: somasim/port_types.hpp) come with
/// this header; `somasim plugin new NAME` writes a plugin folder to start from.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include <spdlog/logger.h>
#include <nlohmann/json.hpp>

#include "somasim/error.hpp"
#include "somasim/plugin_spec.hpp"
#include "somasim/port_types.hpp"
#include "somasim/version.hpp"

namespace somasim {

class NodeRuntime;  // the framework's per-node state (opaque to plugins)
struct RobotSpec;

/// Everything a node may use. The same context is passed to every phase; port references
/// obtained in configure() stay valid for the whole run (data is shared, not copied).
class NodeContext {
 public:
  explicit NodeContext(NodeRuntime& runtime) : rt_(runtime) {}

  const std::string& node_name() const;
  const Params& params() const;
  template <class T>
  T param(const std::string& name) const {
    return params().get<T>(name);
  }

  /// The storage of an output port declared in the spec; write it in step().
  template <class T>
  T& output(const std::string& port) {
    return *static_cast<T*>(port_storage(port, PortDirection::Output, port_type<T>()));
  }
  /// The value wired to an input port (read-only). Throws InputError if an optional input is
  /// unwired: check is_wired() first for optional inputs.
  template <class T>
  const T& input(const std::string& port) const {
    return *static_cast<const T*>(port_storage(port, PortDirection::Input, port_type<T>()));
  }
  bool is_wired(const std::string& input_port) const;
  /// Whether anything reads this node's output `output_port`: another node's input is wired to
  /// it or the experiment records it (tests through the harness count every output as read).
  /// A producer may skip computing outputs nothing reads (e.g. a camera's depth images).
  bool is_read(const std::string& output_port) const;

  double time_s() const;      ///< current simulated time [s]
  std::int64_t tick() const;  ///< current base tick (0-based)
  double rate_hz() const;     ///< this node's rate [Hz]
  double period_s() const { return 1.0 / rate_hz(); }
  double duration_s() const;   ///< the experiment's planned duration [s]
  std::uint64_t seed() const;  ///< the experiment seed
  /// This node's random stream, derived from (experiment seed, node name) only.
  std::mt19937_64& rng();
  spdlog::logger& log();

  /// Ends the run after the current tick (e.g. "500 throws done"); status stays "completed".
  void request_stop(const std::string& reason);
  /// For a node that ends the run when it has done `total` things: `done` of them so far
  /// (e.g. 12 of 200 "objects presented"). The progress line and its ETA use the furthest node;
  /// `what` names the things in it. Cheap: call it whenever `done` changes.
  void report_progress(std::int64_t done, std::int64_t total, const std::string& what);

  /// Records a final figure in metrics.json under `name` (plugins report in finish()).
  void report_metric(const std::string& name, nlohmann::json value);
  /// A path inside the run folder's figures/ directory (created on demand).
  /// `file_name` must be relative and stay inside (no "..", not absolute): else RunError.
  std::filesystem::path figure_path(const std::string& file_name);
  /// A path inside the run folder for other artefacts (e.g. learned state files).
  /// `file_name` is relative to the run folder and may name sub-folders (created on demand);
  /// a name that would leave the run folder (absolute, or with "..") is a RunError.
  std::filesystem::path output_path(const std::string& file_name);
  /// The path in the run folder of the file named by the string parameter `param` (call it in
  /// configure()): InputError naming the node and the parameter if it would leave the run
  /// folder, so a bad name is found before the run, not when the file is written.
  std::filesystem::path output_path_param(const std::string& param);
  /// The path in the run folder of output file `file_name`, named by parameter `param`, claimed
  /// for it: InputError located at the parameter if the name leaves the run folder, is one of
  /// the run's own files (metrics.json, log.txt, experiment.resolved.yaml, manifest.json, a
  /// recorder CSV, figures/) or is claimed by another parameter of the run already.
  std::filesystem::path claim_output_file(const std::string& param, const std::string& file_name);
  /// Resolves a path given in a parameter: relative paths are relative to the experiment file.
  std::filesystem::path resolve_input_path(const std::string& path) const;

  /// Throws InputError naming the node and parameter, with the parameter's file location.
  [[noreturn]] void param_error(const std::string& param, const std::string& message) const;
  /// Throws InputError naming the node, located at its entry in the experiment file (for
  /// problems of the node as a whole, e.g. how its ports are wired).
  [[noreturn]] void node_error(const std::string& message) const;

  /// The robot named by this node's string parameter `param` in the experiment's `robots:`
  /// section; an empty name picks the experiment's only robot. InputError (located at the
  /// parameter) when there is no such robot. Domain libraries build on this (the robot
  /// library's experiment_robot() loads the model once per run).
  const RobotSpec& robot_spec(const std::string& param) const;

  /// A value shared by every node of this run, made by `make` on the first request for `key`
  /// and kept until the run ends (e.g. a robot model loaded once per run). Not thread-safe:
  /// call it from configure().
  template <class T>
  std::shared_ptr<const T> run_shared(const std::string& key,
                                      const std::function<std::shared_ptr<const T>()>& make) {
    return std::static_pointer_cast<const T>(
        run_shared_erased(key, [&make]() -> std::shared_ptr<const void> { return make(); }));
  }

 private:
  std::shared_ptr<const void> run_shared_erased(
      const std::string& key, const std::function<std::shared_ptr<const void>()>& make);
  void* port_storage(const std::string& port, PortDirection direction,
                     const PortTypeInfo& type) const;
  NodeRuntime& rt_;
};

/// Base class of every plugin. Exceptions: InputError from configure() means bad input;
/// any exception from start/step/finish fails the run (outputs are still flushed).
class Plugin {
 public:
  virtual ~Plugin() = default;
  /// Read parameters, take references to ports, validate; no simulation yet.
  virtual void configure(NodeContext& ctx) = 0;
  /// Called once at t = 0 before the first step.
  virtual void start(NodeContext& /*ctx*/) {}
  /// Called at every tick of this node's rate (t = k / rate_hz).
  virtual void step(NodeContext& ctx) = 0;
  /// Called once at the end, also after a failure or interruption: report metrics, figures.
  virtual void finish(NodeContext& /*ctx*/) {}
};

/// Collects the plugins of one shared library.
class PluginRegistrar {
 public:
  template <class P>
  void add() {
    PluginSpec spec = P::spec();
    spec.factory = [] { return std::unique_ptr<Plugin>(new P()); };
    specs_.push_back(std::move(spec));
  }
  std::vector<PluginSpec>& specs() { return specs_; }

 private:
  std::vector<PluginSpec> specs_;
};

/// The C entry point every plugin library exports (see SOMASIM_PLUGIN_LIBRARY).
struct PluginLibraryEntry {
  const char* interface_version;  ///< must equal kPluginInterfaceVersion of the loader
  void (*register_plugins)(PluginRegistrar& registrar);
};

}  // namespace somasim

/// Name of the exported entry symbol.
#define SOMASIM_PLUGIN_ENTRY_SYMBOL "somasim_plugin_entry"

/// Defines the library's entry point; the body registers plugins with `registrar.add<P>()`.
#define SOMASIM_PLUGIN_LIBRARY(registrar)                                                \
  static void somasim_register_plugins_(::somasim::PluginRegistrar& registrar);          \
  extern "C" __attribute__((visibility("default"))) const ::somasim::PluginLibraryEntry* \
  somasim_plugin_entry() {                                                               \
    static const ::somasim::PluginLibraryEntry entry{::somasim::kPluginInterfaceVersion, \
                                                     &somasim_register_plugins_};        \
    return &entry;                                                                       \
  }                                                                                      \
  static void somasim_register_plugins_(::somasim::PluginRegistrar& registrar)
