// Word-list parameters and the experiment's robots: values, defaults and every error message.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/testing/harness.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {

using somasim::testing::Harness;

std::string load_error(const std::string& yaml) {
  PluginRegistry registry({kTestPluginDir});
  try {
    load_experiment_text(yaml, "exp.yaml", "/base", registry);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> words_of(const std::string& words_yaml) {
  PluginRegistry registry({kTestPluginDir});
  const Experiment e = load_experiment_text(
      "experiment: t\nduration_s: 1\nnodes:\n  n: {plugin: list_and_robot, params: {words: " +
          words_yaml + "}}\n",
      "exp.yaml", "/base", registry);
  return e.nodes[0].params.get<std::vector<std::string>>("words");
}

TEST(WordLists, ASequenceOrOneStringOfWords) {
  const std::vector<std::string> ab = {"left_forearm", "right_palm"};
  EXPECT_EQ(words_of("[left_forearm, right_palm]"), ab);
  EXPECT_EQ(words_of("left_forearm right_palm"), ab);
  EXPECT_EQ(words_of("'left_forearm, right_palm'"), ab);
  EXPECT_EQ(words_of("''"), std::vector<std::string>{});
  EXPECT_EQ(words_of("[]"), std::vector<std::string>{});
}

TEST(WordLists, DefaultsAndTheResolvedFile) {
  PluginRegistry registry({kTestPluginDir});
  const Experiment e =
      load_experiment_text("experiment: t\nduration_s: 1\nnodes:\n  n: {plugin: list_and_robot}\n",
                           "exp.yaml", "/base", registry);
  EXPECT_EQ(e.nodes[0].params.get<std::vector<std::string>>("words"),
            (std::vector<std::string>{"a", "b"}));
  EXPECT_NE(e.resolved_yaml().find("words: [\"a\", \"b\"]"), std::string::npos)
      << e.resolved_yaml();
}

TEST(WordLists, BadElementsAreLocatedErrors) {
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nnodes:\n  n: {plugin: list_and_robot, "
                       "params: {words: [a, [b]]}}\n"),
            "exp.yaml:4:47: node 'n', key 'params.words': expected a list of words, got an "
            "element a list");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nnodes:\n  n: {plugin: list_and_robot, "
                       "params: {words: {a: 1}}}\n"),
            "exp.yaml:4:47: node 'n', key 'params.words': expected a list of words, got a map");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nnodes:\n  n: {plugin: list_and_robot, "
                       "params: {colours: red blu}}\n"),
            "exp.yaml:4:49: node 'n', key 'params.colours': expected a list of words: one of "
            "red, green, got an element 'blu'");
}

const std::string kTwoRobots =
    "robots:\n  icub: " SOMASIM_SOURCE_DIR
    "/assets/robots/icub_v1.yaml\n  icub2: " SOMASIM_SOURCE_DIR "/assets/robots/icub_v2.yaml\n";
const std::string kOneRobot = "robots: {icub: " SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml}\n";

TEST(Robots, NodesNameTheRobotOrUseTheOnlyOne) {
  Harness h(kTwoRobots + R"(
nodes:
  a: {plugin: list_and_robot, params: {use_robot: true, robot: icub2}}
  b: {plugin: list_and_robot, params: {use_robot: true, robot: icub}}
)",
            {kTestPluginDir});
  h.finish();
  EXPECT_EQ(h.metric("a", "robot_file"), "icub_v2.yaml");
  EXPECT_EQ(h.metric("b", "robot_file"), "icub_v1.yaml");

  Harness one(kOneRobot + "nodes:\n  a: {plugin: list_and_robot, params: {use_robot: true}}\n",
              {kTestPluginDir});
  one.finish();
  EXPECT_EQ(one.metric("a", "robot_file"), "icub_v1.yaml");
}

TEST(Robots, RunSharedValuesAreMadeOncePerRun) {
  const std::string graph = kOneRobot + R"(
nodes:
  a: {plugin: list_and_robot, params: {use_robot: true}}
  b: {plugin: list_and_robot, params: {use_robot: true}}
)";
  Harness first(graph, {kTestPluginDir});
  first.finish();
  EXPECT_EQ(first.metric("a", "shared"), first.metric("b", "shared"));
  Harness second(graph, {kTestPluginDir});  // a new run makes its own
  second.finish();
  EXPECT_EQ(second.metric("a", "shared").get<int>(), first.metric("a", "shared").get<int>() + 1);
}

std::string configure_error(const std::string& yaml) {
  try {
    Harness h(yaml, {kTestPluginDir});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Robots, ErrorsNameTheRobotsSectionAndTheParameter) {
  EXPECT_EQ(configure_error(kTwoRobots + "nodes:\n  a: {plugin: list_and_robot, params: "
                                         "{use_robot: true, robot: icb}}\n"),
            "<inline>:5:64: node 'a', key 'params.robot': no robot 'icb' in the experiment's "
            "'robots:' section (declared: 'icub', 'icub2')");
  EXPECT_EQ(configure_error(kTwoRobots + "nodes:\n  a: {plugin: list_and_robot, params: "
                                         "{use_robot: true}}\n"),
            "<inline>:5:3: node 'a', key 'params.robot': the experiment declares several robots "
            "('icub', 'icub2'): name one");
  EXPECT_EQ(configure_error("nodes:\n  a: {plugin: list_and_robot, params: {use_robot: true}}\n"),
            "<inline>:2:3: node 'a', key 'params.robot': no robot: declare one in the "
            "experiment's 'robots:' section (NAME: description file)");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nrobots: {icub: missing.yaml}\nnodes:\n  n: "
                       "{plugin: list_and_robot}\n"),
            "exp.yaml:3:16: key 'robots.icub': robot description file '/base/missing.yaml' does "
            "not exist");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nrobots: [icub]\nnodes:\n  n: "
                       "{plugin: list_and_robot}\n"),
            "exp.yaml:3:9: key 'robots': expected a map of robot names to description files, got "
            "a list");
  EXPECT_EQ(load_error("experiment: t\nduration_s: 1\nrobots: {'a b': x.yaml}\nnodes:\n  n: "
                       "{plugin: list_and_robot}\n"),
            "exp.yaml:3:10: key 'robots': robot names are letters, digits and '_', got 'a b'");
}

}  // namespace
}  // namespace somasim::test
