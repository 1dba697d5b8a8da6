#pragma once
/// @file
/// An experiment: a validated graph of plugin instances loaded from YAML.
///
/// File format (all keys; unknown keys are errors):
/// @code
///   experiment: name            # required
///   description: text           # optional
///   seed: 7                     # integer >= 0, default 0
///   duration_s: 60              # required, > 0 [s]; plugins may stop the run earlier
///   base_rate_hz: 1000          # scheduler tick [Hz], default 1000
///   base_dir: /abs/dir          # relative paths in params resolve here; default: file's dir
///   plugin_libraries: [lib.so]  # extra plugin libraries loaded by path (relative to base_dir)
///   robots:                     # the robots of the experiment: NAME: description file
///     icub: ../assets/robots/icub_v1.yaml   # (relative to base_dir); loaded once per run
///   nodes:
///     NAME:
///       plugin: PLUGIN          # required
///       rate_hz: 20             # default base_rate_hz; must divide it
///       params: {KEY: VALUE}    # checked against the plugin's schema
///       inputs:                 # PORT: NODE.PORT, or a delayed (feedback) edge:
///         cmd: {from: ctrl.cmd, delayed: true}   # reads the previous tick's value
///   record: [NODE.PORT, ...]    # one CSV per port in the run folder
/// @endcode
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "somasim/param.hpp"
#include "somasim/plugin_spec.hpp"
#include "somasim/source_location.hpp"

namespace somasim {

class PluginRegistry;

/// One wired input of a node.
struct InputWire {
  std::string port;       ///< the consumer's input port
  std::string from_node;  ///< producer node ("harness" for harness-fed inputs in tests)
  std::string from_port;
  bool delayed = false;  ///< reads the producer's value of the previous base tick
  SourceLocation where;
};

struct NodeSpec {
  std::string name;
  std::string plugin;
  double rate_hz = 0.0;
  int period_ticks = 1;  ///< base ticks between two steps (base_rate_hz / rate_hz)
  const PluginSpec* spec = nullptr;
  Params params;
  std::map<std::string, SourceLocation> param_locations;  ///< where each given param was set
  std::vector<InputWire> inputs;
  SourceLocation where;
};

/// A robot of the experiment (`robots:` section). Plugins name it in their `robot` parameter;
/// the robot library loads the file once per run (somasim/robot/experiment_robot.hpp).
struct RobotSpec {
  std::string name;
  std::filesystem::path file;  ///< resolved against base_dir
  SourceLocation where;        ///< the entry in the file
};

/// How a recorded port is written: `files` (its type's own files: a CSV, or a folder of
/// images) or `video` (an image port as NODE.PORT.mp4).
enum class RecordAs { kFiles, kVideo };

struct RecordSpec {
  std::string node, port;
  SourceLocation where;
  RecordAs as = RecordAs::kFiles;  ///< `record: [{port: NODE.PORT, as: video}]`
};

/// A `--set path=value` override from the command line.
struct Override {
  std::string path;   ///< dotted path, e.g. "nodes.pps.params.threshold"
  std::string value;  ///< YAML text of the new value
};

struct LoadOptions {
  std::vector<Override> overrides;
  std::optional<std::uint64_t> seed;  ///< replaces the file's seed
  /// Test harness: inputs may be wired to the pseudo-node "harness", fed by the test.
  bool allow_harness_inputs = false;
  /// Fill in `experiment` and `duration_s` when missing (inline test graphs).
  bool defaults_for_tests = false;
};

/// A validated experiment, ready to run.
struct Experiment {
  std::filesystem::path file;  ///< as given (for messages)
  std::filesystem::path base_dir;
  std::string name, description;
  std::uint64_t seed = 0;
  double duration_s = 0.0;
  double base_rate_hz = 1000.0;
  std::vector<std::string> plugin_libraries;
  std::vector<RobotSpec> robots;  ///< in file order
  std::vector<NodeSpec> nodes;    ///< in file order
  std::vector<int> order;         ///< indices into `nodes`, topological order of inputs
  std::vector<RecordSpec> records;

  const NodeSpec* find_node(const std::string& name) const;
  const RobotSpec* find_robot(const std::string& name) const;
  /// The experiment with every default filled in: running it again repeats this run exactly.
  std::string resolved_yaml() const;
  /// The graph in Graphviz DOT (delayed edges dashed).
  std::string graphviz() const;
};

/// Loads, overrides and validates an experiment file. Every problem of the file is collected
/// and thrown together as one InputError ("file:line:col: node 'n', key 'k': ...").
Experiment load_experiment_file(const std::filesystem::path& file, PluginRegistry& registry,
                                const LoadOptions& options = {});

/// The same from YAML text; `display_name` stands for the file in messages and `base_dir`
/// resolves relative paths.
Experiment load_experiment_text(const std::string& yaml, const std::string& display_name,
                                const std::filesystem::path& base_dir, PluginRegistry& registry,
                                const LoadOptions& options = {});

}  // namespace somasim
