// Loading an experiment: every error message a user can meet, asserted in full (DESIGN §8).
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {

const std::string kSearched = "searched: " + kTestPluginDir + " (libsomasim_test_plugins.so)";
const std::string kNoEntryWhy =
    "no entry point 'somasim_plugin_entry' among its dynamic symbols (is SOMASIM_PLUGIN_LIBRARY "
    "missing?); not loaded";
const std::string kOldApiWhy =
    "built for plugin interface 'somasim-plugin-api/0', this somasim needs "
    "'somasim-plugin-api/6' (rebuild the plugin)";

// Loads `yaml` as "exp.yaml" against the test plugins (plus `extra_dirs`); returns the
// InputError's message, or "" if it loaded.
std::string load_error(const std::string& yaml, const LoadOptions& options = {},
                       std::vector<std::filesystem::path> dirs = {kTestPluginDir}) {
  PluginRegistry registry(std::move(dirs));
  try {
    load_experiment_text(yaml, "exp.yaml", "/base", registry, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Experiment load_ok(const std::string& yaml, PluginRegistry& registry,
                   const LoadOptions& options = {}) {
  return load_experiment_text(yaml, "exp.yaml", "/base", registry, options);
}

// A valid two-node experiment, used as the starting point of most cases below.
const std::string kValid = R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  s: {plugin: adder, inputs: {a: c.value}}
record: [s.sum]
)";

TEST(ExperimentLoader, ValidFileLoadsWithDefaultsAndOrder) {
  PluginRegistry registry({kTestPluginDir});
  const Experiment exp = load_ok(kValid, registry);
  EXPECT_EQ(exp.name, "t");
  EXPECT_EQ(exp.seed, 0u);
  EXPECT_EQ(exp.base_rate_hz, 1000.0);
  ASSERT_EQ(exp.nodes.size(), 2u);
  EXPECT_EQ(exp.nodes[0].params.get<double>("increment"), 1.0);
  EXPECT_EQ(exp.nodes[0].params.get<std::string>("mode"), "plain");
  EXPECT_EQ(exp.nodes[1].period_ticks, 1);
  EXPECT_EQ(exp.order, (std::vector<int>{0, 1}));
  EXPECT_EQ(exp.base_dir, "/base");
}

TEST(ExperimentLoader, UnknownPluginSuggestsAndReportsSearch) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: countr, params: {start: 0}}
)"),
            "exp.yaml:4:15: node 'c', key 'plugin': unknown plugin 'countr' (did you mean "
            "'counter'?); " +
                kSearched);
}

TEST(ExperimentLoader, UnknownPluginReportsRejectedLibrariesAndMissingDirs) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  x: {plugin: nothing_like_it}
)",
                       {}, {kTestPluginDir, kBadPluginDir, "/no/such/dir"}),
            "exp.yaml:4:15: node 'x', key 'plugin': unknown plugin 'nothing_like_it'; " +
                kSearched + "; " + kBadPluginDir + " (libsomasim_test_no_entry.so [rejected: " +
                kNoEntryWhy + "], libsomasim_test_old_api.so [rejected: " + kOldApiWhy +
                "]); /no/such/dir (not a directory)");
}

TEST(ExperimentLoader, EmptySearchPathIsReported) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  x: {plugin: counter}
)",
                       {}, {}),
            "exp.yaml:4:15: node 'x', key 'plugin': unknown plugin 'counter'; searched: (empty "
            "search path)");
}

TEST(ExperimentLoader, UnknownTopLevelKey) {
  EXPECT_EQ(load_error("experiment: t\nduration: 1\nnodes: {}\n"),
            "2 errors:\n"
            "  exp.yaml:1:1: key 'duration_s': missing required key (expected a number)\n"
            "  exp.yaml:2:1: key 'duration': unknown key (did you mean 'duration_s'?); expected "
            "one of: experiment, description, seed, duration_s, base_rate_hz, base_dir, "
            "plugin_libraries, robots, nodes, record");
}

TEST(ExperimentLoader, UnknownNodeKey) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, rate: 10, params: {start: 0}}
)"),
            "exp.yaml:4:24: node 'c', key 'rate': unknown key (did you mean 'rate_hz'?); "
            "expected one of: plugin, rate_hz, params, inputs, description");
}

TEST(ExperimentLoader, UnknownParam) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0, incremnt: 2}}
)"),
            "exp.yaml:4:43: node 'c', key 'params.incremnt': unknown parameter of plugin "
            "'counter' (did you mean 'increment'?); expected one of: start, increment, mode, "
            "stop_after, offset, fail");
}

TEST(ExperimentLoader, UnknownWireKey) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  s: {plugin: adder, inputs: {a: {from: c.value, delay: true}}}
)"),
            "exp.yaml:5:50: node 's', key 'inputs.a.delay': unknown key (did you mean "
            "'delayed'?); expected one of: from, delayed");
}

TEST(ExperimentLoader, MissingRequiredParameter) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter}
)"),
            "exp.yaml:4:6: node 'c', key 'params.start': missing required parameter of plugin "
            "'counter' (expected a number: first value (required))");
}

TEST(ExperimentLoader, WrongType) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: zero, stop_after: 1.5, fail: maybe, offset: 3}}
)"),
            "4 errors:\n"
            "  exp.yaml:4:40: node 'c', key 'params.start': expected a number, got 'zero'\n"
            "  exp.yaml:4:58: node 'c', key 'params.stop_after': expected an integer >= 0, got "
            "'1.5'\n"
            "  exp.yaml:4:69: node 'c', key 'params.fail': expected a boolean (true/false), got "
            "'maybe'\n"
            "  exp.yaml:4:84: node 'c', key 'params.offset': expected a list of 3 numbers [m], "
            "got '3'");
}

TEST(ExperimentLoader, ValueOutOfRangeAndWrongSizeAndChoice) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c:
    plugin: counter
    params:
      start: 0
      increment: 101
      stop_after: -1
      offset: [1, 2]
      mode: loud
)"),
            "4 errors:\n"
            "  exp.yaml:8:18: node 'c', key 'params.increment': value 101 is out of range; "
            "expected a number in [-100, 100]\n"
            "  exp.yaml:9:19: node 'c', key 'params.stop_after': value -1 is out of range; "
            "expected an integer >= 0\n"
            "  exp.yaml:10:15: node 'c', key 'params.offset': expected a list of 3 numbers [m], "
            "got 2 numbers\n"
            "  exp.yaml:11:13: node 'c', key 'params.mode': expected a string: one of plain, "
            "noisy, got 'loud'");
}

TEST(ExperimentLoader, NanAndInfAreRejected) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: .inf
nodes:
  c: {plugin: counter, params: {start: .nan, increment: -.inf, offset: [0, .inf, 0]}}
)"),
            "4 errors:\n"
            "  exp.yaml:2:13: key 'duration_s': expected a finite number, got '.inf'\n"
            "  exp.yaml:4:40: node 'c', key 'params.start': expected a finite number, got "
            "'.nan'\n"
            "  exp.yaml:4:57: node 'c', key 'params.increment': expected a finite number, got "
            "'-.inf'\n"
            "  exp.yaml:4:72: node 'c', key 'params.offset': expected a finite number, got "
            "'.inf'");
}

TEST(ExperimentLoader, DuplicateNode) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  c: {plugin: counter, params: {start: 1}}
)"),
            "exp.yaml:5:3: node 'c': duplicate node name (first defined at exp.yaml:4:3)");
}

TEST(ExperimentLoader, DuplicateKeys) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
duration_s: 2
nodes:
  c: {plugin: counter, params: {start: 0, start: 1}}
)"),
            "2 errors:\n"
            "  exp.yaml:3:1: key 'duration_s': duplicate key (first defined at exp.yaml:2:1)\n"
            "  exp.yaml:5:43: node 'c', key 'params.start': duplicate key (first defined at "
            "exp.yaml:5:33)");
}

TEST(ExperimentLoader, InputFromMissingNode) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  cnt: {plugin: counter, params: {start: 0}}
  s: {plugin: adder, inputs: {a: cn.value}}
)"),
            "exp.yaml:5:34: node 's', key 'inputs.a': no node 'cn' (did you mean 'cnt'?); "
            "nodes: cnt, s");
}

TEST(ExperimentLoader, InputFromMissingPort) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  s: {plugin: adder, inputs: {a: c.valu}}
)"),
            "exp.yaml:5:34: node 's', key 'inputs.a': node 'c' (plugin 'counter') has no output "
            "'valu' (did you mean 'value'?); outputs: value, vector");
}

TEST(ExperimentLoader, InputToMissingPortAndUnwiredRequiredInput) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  s: {plugin: adder, inputs: {aa: c.value}}
)"),
            "2 errors:\n"
            "  exp.yaml:5:3: node 's', key 'inputs.a': required input is not wired (expected "
            "'node.port' giving 'scalar': first term)\n"
            "  exp.yaml:5:35: node 's', key 'inputs.aa': plugin 'adder' has no input 'aa' (did "
            "you mean 'a'?); inputs: a, b");
}

TEST(ExperimentLoader, PortTypeMismatch) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  v: {plugin: vector_sink, inputs: {in: c.value}}
)"),
            "exp.yaml:5:41: node 'v', key 'inputs.in': type mismatch: input 'in' takes 'vector3' "
            "but 'c.value' gives 'scalar'");
}

const std::string kCycle = R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
  a: {plugin: adder, inputs: {a: c.value, b: b.sum}}
  b: {plugin: adder, inputs: {a: a.sum}}
)";

TEST(ExperimentLoader, CycleWithoutDelayedEdge) {
  EXPECT_EQ(load_error(kCycle),
            "exp.yaml:5:3: node 'a', key 'inputs': cycle without a delayed edge: a -> b -> a "
            "(data flows left to right; mark one of these inputs as {from: node.port, delayed: "
            "true} to read the previous tick's value)");
}

TEST(ExperimentLoader, DelayedEdgeBreaksTheCycle) {
  std::string yaml = kCycle;
  yaml.replace(yaml.find("b: b.sum"), 8, "b: {from: b.sum, delayed: true}");
  PluginRegistry registry({kTestPluginDir});
  const Experiment exp = load_ok(yaml, registry);
  EXPECT_EQ(exp.order, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(exp.nodes[1].inputs[1].delayed);
}

TEST(ExperimentLoader, RateMustDivideBaseRate) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
base_rate_hz: 1000
nodes:
  c: {plugin: counter, rate_hz: 300, params: {start: 0}}
  d: {plugin: counter, rate_hz: 2000, params: {start: 0}}
  e: {plugin: counter, rate_hz: -5, params: {start: 0}}
)"),
            "3 errors:\n"
            "  exp.yaml:5:33: node 'c', key 'rate_hz': rate 300 Hz does not divide the base rate "
            "1000 Hz (base_rate_hz / rate_hz must be a whole number >= 1)\n"
            "  exp.yaml:6:33: node 'd', key 'rate_hz': rate 2000 Hz does not divide the base rate "
            "1000 Hz (base_rate_hz / rate_hz must be a whole number >= 1)\n"
            "  exp.yaml:7:33: node 'e', key 'rate_hz': expected a finite number > 0 [Hz], got "
            "'-5'");
}

TEST(ExperimentLoader, MissingFile) {
  PluginRegistry registry({kTestPluginDir});
  try {
    load_experiment_file("/no/such/exp.yaml", registry);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "experiment file '/no/such/exp.yaml' does not exist");
  }
}

TEST(ExperimentLoader, YamlSyntaxErrorHasLineAndColumn) {
  TempDir dir;
  const auto file = dir / "broken.yaml";
  write_file(file, "experiment: t\nduration_s: 1\nnodes:\n  c: {plugin: counter\n");
  PluginRegistry registry({kTestPluginDir});
  try {
    load_experiment_file(file, registry);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file.string() +
                  ":5:1: YAML syntax error: end of map flow not found (the '{' opened at " +
                  file.string() + ":4:6 is never closed)");
  }
}

TEST(ExperimentLoader, RootMustBeAMap) {
  EXPECT_EQ(load_error("- a\n- b\n"),
            "exp.yaml:1:1: expected a map with the keys 'experiment', 'duration_s' and 'nodes', "
            "got a list");
}

TEST(ExperimentLoader, PluginLibraryWithoutEntryPoint) {
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nplugin_libraries: [" + kNoEntryLib +
                       "]\nnodes: {}\n"),
            "exp.yaml:3:20: key 'plugin_libraries': plugin library '" + kNoEntryLib +
                "' rejected: " + kNoEntryWhy);
}

TEST(ExperimentLoader, PluginLibraryForAnotherInterfaceVersion) {
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nplugin_libraries: [" + kOldApiLib +
                       "]\nnodes: {}\n"),
            "exp.yaml:3:20: key 'plugin_libraries': plugin library '" + kOldApiLib +
                "' rejected: " + kOldApiWhy);
}

TEST(ExperimentLoader, PluginLibraryThatDoesNotExist) {
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nplugin_libraries: [libs/none.so]\n"
                       "nodes: {}\n"),
            "exp.yaml:3:20: key 'plugin_libraries': plugin library '/base/libs/none.so' does "
            "not exist");
}

TEST(ExperimentLoader, PluginLibraryLoadedByPathProvidesPlugins) {
  PluginRegistry registry({});  // nothing on the search path
  const Experiment exp =
      load_ok("experiment: t\nduration_s: 1\nplugin_libraries: [" + kTestPluginLib +
                  "]\nnodes:\n  c: {plugin: counter, params: {start: 0}}\n",
              registry);
  EXPECT_EQ(exp.plugin_libraries, (std::vector<std::string>{kTestPluginLib}));
  EXPECT_EQ(exp.nodes[0].spec->library_path, kTestPluginLib);
}

// A node written without `params:` takes a parameter from --set (the map is made).
TEST(ExperimentLoader, SetGivesAParameterToANodeWrittenWithoutParams) {
  LoadOptions options;
  options.overrides = {{"nodes.c.params.start", "3"}};
  PluginRegistry registry({kTestPluginDir});
  const Experiment exp =
      load_ok("experiment: t\nduration_s: 1\nnodes:\n  c: {plugin: counter}\n", registry, options);
  EXPECT_EQ(exp.nodes[0].params.get<double>("start"), 3.0);
}

// --set adds a whole node when its value names a plugin (a spectator for any config); a value
// without one is a typo of a node name, refused with the nearest name.
TEST(ExperimentLoader, SetAddsANodeGivenItsPlugin) {
  LoadOptions options;
  options.overrides = {{"nodes.extra", "{plugin: counter, params: {start: 4}}"}};
  PluginRegistry registry({kTestPluginDir});
  const Experiment exp =
      load_ok("experiment: t\nduration_s: 1\nnodes:\n  c: {plugin: counter, params: {start: 1}}\n",
              registry, options);
  ASSERT_EQ(exp.nodes.size(), 2u);
  EXPECT_EQ(exp.nodes[1].name, "extra");
  EXPECT_EQ(exp.nodes[1].params.get<double>("start"), 4.0);
  options.overrides = {{"nodes.cc", "{params: {start: 4}}"}};
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nnodes:\n  c: {plugin: counter, params: "
                       "{start: 1}}\n",
                       options),
            "--set 'nodes.cc={params: {start: 4}}': there is no node 'cc' in exp.yaml (did you "
            "mean 'c'?); a new node is added by a map with its plugin, e.g. --set "
            "'nodes.cc={plugin: NAME, inputs: {...}}'");
}

TEST(ExperimentLoader, SetOnMissingPath) {
  LoadOptions options;
  options.overrides = {{"nodes.cc.params.start", "1"}};
  EXPECT_EQ(load_error(kValid, options),
            "--set 'nodes.cc.params.start=1': no map 'nodes.cc' in exp.yaml (did you mean 'c'?)");
  options.overrides = {{"nodes.c.params.strat", "1"}};
  EXPECT_EQ(load_error(kValid, options),
            "--set 'nodes.c.params.strat=1': 'nodes.c.params.strat' does not exist in exp.yaml "
            "and is not a key that can be set there (did you mean 'start'?)");
  options.overrides = {{"nodes..x", "1"}};
  EXPECT_EQ(load_error(kValid, options),
            "--set 'nodes..x=1': expected a dotted path such as nodes.NODE.params.NAME");
  options.overrides = {{"seed", "[1"}};
  EXPECT_EQ(load_error(kValid, options),
            "--set 'seed=[1': the value is not valid YAML: end of sequence flow not found");
}

TEST(ExperimentLoader, SetWithBadValueNamesTheOverride) {
  LoadOptions options;
  options.overrides = {{"nodes.c.params.increment", "abc"}};
  EXPECT_EQ(load_error(kValid, options),
            "--set nodes.c.params.increment=abc: node 'c', key 'params.increment': expected a "
            "number in [-100, 100], got 'abc'");
}

TEST(ExperimentLoader, SetOverridesExistingAndAbsentValues) {
  PluginRegistry registry({kTestPluginDir});
  LoadOptions options;
  options.overrides = {{"nodes.c.params.start", "5"},        // in the file
                       {"nodes.c.params.increment", "2.5"},  // absent from the file
                       {"nodes.s.rate_hz", "500"},
                       {"seed", "9"}};
  const Experiment exp = load_ok(kValid, registry, options);
  EXPECT_EQ(exp.nodes[0].params.get<double>("start"), 5.0);
  EXPECT_EQ(exp.nodes[0].params.get<double>("increment"), 2.5);
  EXPECT_EQ(exp.nodes[1].period_ticks, 2);
  EXPECT_EQ(exp.seed, 9u);
  options.seed = 11;  // --seed wins over the file and --set
  EXPECT_EQ(load_ok(kValid, registry, options).seed, 11u);
}

TEST(ExperimentLoader, SeveralErrorsReportedTogetherInFileOrder) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 0
nodes:
  s: {plugin: adder, inputs: {a: nowhere.value}}
  c: {plugin: countr}
  v: {plugin: vector_sink, inputs: {in: s.sum}}
record: [c.value, s.total, nodot]
)"),
            "6 errors:\n"
            "  exp.yaml:2:13: key 'duration_s': expected a number > 0, got 0\n"
            "  exp.yaml:4:34: node 's', key 'inputs.a': no node 'nowhere'; nodes: s, c, v\n"
            "  exp.yaml:5:15: node 'c', key 'plugin': unknown plugin 'countr' (did you mean "
            "'counter'?); " +
                kSearched +
                "\n"
                "  exp.yaml:6:41: node 'v', key 'inputs.in': type mismatch: input 'in' takes "
                "'vector3' but 's.sum' gives 'scalar'\n"
                "  exp.yaml:7:19: key 'record': node 's' (plugin 'adder') has no output 'total'; "
                "outputs: sum\n"
                "  exp.yaml:7:28: key 'record': expected 'node.port' or {port: node.port, as: "
                "video}, got 'nodot'");
}

// The map form of a record entry: `as: video` for image ports only; its keys and values checked.
TEST(ExperimentLoader, RecordEntriesAsVideoAreCheckedWhereTheyAre) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0}}
record: [{port: c.value, as: video}, {port: c.value, as: film}, {as: video}, {port: c.value, fps: 3}]
)"),
            "4 errors:\n"
            "  exp.yaml:5:17: key 'record': port 'c.value' of type 'scalar' cannot be recorded "
            "as video (only image ports can; record it as files)\n"
            "  exp.yaml:5:58: key 'record.as': expected one of: files, video; got 'film'\n"
            "  exp.yaml:5:65: key 'record': missing 'port: node.port'\n"
            "  exp.yaml:5:94: key 'record.fps': unknown key (did you mean 'as'?); expected one of: "
            "port, as");
}

TEST(ExperimentLoader, MissingRequiredTopLevelKeys) {
  EXPECT_EQ(
      load_error("seed: -1\n"),
      "4 errors:\n"
      "  exp.yaml:1:1: key 'experiment': missing required key (expected a string)\n"
      "  exp.yaml:1:1: key 'duration_s': missing required key (expected a number)\n"
      "  exp.yaml:1:1: key 'nodes': missing required key (expected a map of node names to "
      "nodes)\n"
      "  exp.yaml:1:7: key 'seed': expected an integer in [0, 18446744073709551615], got '-1'");
}

TEST(ExperimentLoader, MalformedShapes) {
  EXPECT_EQ(load_error(R"(experiment: t
duration_s: 1
plugin_libraries: lib.so
nodes:
  a.b: {plugin: counter}
  harness: {plugin: counter}
  n: 3
  c: {plugin: counter, params: [1]}
  s: {plugin: adder, inputs: {a: c, b: {from: c.value, delayed: maybe}}}
  t: {plugin: adder, inputs: {a: {delayed: true}}}
  u: {plugin: adder, inputs: [c.value]}
record: s.sum
)"),
            "10 errors:\n"
            "  exp.yaml:3:19: key 'plugin_libraries': expected a list of paths, got 'lib.so'\n"
            "  exp.yaml:5:3: node 'a.b': invalid node name (letters, digits, '_' and '-'; "
            "'harness' is reserved)\n"
            "  exp.yaml:6:3: node 'harness': invalid node name (letters, digits, '_' and '-'; "
            "'harness' is reserved)\n"
            "  exp.yaml:7:6: node 'n': expected a map with 'plugin', 'params', 'inputs', got '3'\n"
            "  exp.yaml:8:32: node 'c', key 'params': expected a map of parameter names to values, "
            "got a list\n"
            "  exp.yaml:9:34: node 's', key 'inputs.a': expected 'node.port' or {from: node.port, "
            "delayed: true}, got 'c'\n"
            "  exp.yaml:9:65: node 's', key 'inputs.b.delayed': expected a boolean (true/false), "
            "got 'maybe'\n"
            "  exp.yaml:10:34: node 't', key 'inputs.a': missing 'from: node.port'\n"
            "  exp.yaml:11:30: node 'u', key 'inputs': expected a map of input ports to "
            "'node.port', got a list\n"
            "  exp.yaml:12:9: key 'record': expected a list of 'node.port', got 's.sum'");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nnodes: [a]\n"),
            "exp.yaml:3:8: key 'nodes': expected a map of node names to nodes, got a list");
}

}  // namespace
}  // namespace somasim::test
