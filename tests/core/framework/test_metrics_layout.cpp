// metrics.json's flat names (somasim/metrics_layout.hpp), over generated node sections.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "somasim/metrics_layout.hpp"

namespace somasim {
namespace {

nlohmann::json example() {
  return nlohmann::json::parse(R"({
    "experiment": "e", "status": "completed", "error": "", "seed": 4,
    "versions": {"somasim": "0.1.0"},
    "nodes": {
      "world": {"steps": 10, "contacts": 3},
      "thrower": {"steps": 5, "thrown": 7, "status": "busy",
                  "per_part": {"left_forearm": {"thrown": 4, "hit": 2}, "right_palm": {"thrown": 3}},
                  "ids": [1, 2, 3]}
    }})");
}

TEST(MetricsLayout, UniqueNamesArePlainClashesAreQualified) {
  std::map<std::string, nlohmann::json> flat;
  for (const auto& [name, value] : node_metrics_by_flat_name(example())) flat[name] = value;
  EXPECT_EQ(flat.at("world.steps"), 10);
  EXPECT_EQ(flat.at("thrower.steps"), 5);
  EXPECT_EQ(flat.at("contacts"), 3);
  EXPECT_EQ(flat.at("thrown"), 7);
  EXPECT_EQ(flat.at("thrower.status"), "busy");  // a run key's name
  EXPECT_EQ(flat.count("steps"), 0u);
}

TEST(MetricsLayout, FindsRunKeysFlatNamesAndNestedKeys) {
  const auto m = example();
  EXPECT_EQ(find_metric(m, "status"), "completed");
  EXPECT_EQ(find_metric(m, "versions.somasim"), "0.1.0");
  EXPECT_EQ(find_metric(m, "thrown"), 7);
  EXPECT_EQ(find_metric(m, "per_part.left_forearm.hit"), 2);
  EXPECT_EQ(find_metric(m, "per_part.right_palm"), nlohmann::json({{"thrown", 3}}));
  EXPECT_EQ(find_metric(m, "thrower.status"), "busy");
  EXPECT_FALSE(find_metric(m, "steps"));
  EXPECT_FALSE(find_metric(m, "per_part.elbow"));
  EXPECT_FALSE(find_metric(m, "nodes"));
  EXPECT_FALSE(find_metric(nlohmann::json::array(), "x"));
}

TEST(MetricsLayout, FlattensScalarsAndLeavesListsOut) {
  std::map<std::string, nlohmann::json> flat;
  for (const auto& [name, value] : flatten_metrics(example())) flat[name] = value;
  EXPECT_EQ(flat.at("per_part.left_forearm.thrown"), 4);
  EXPECT_EQ(flat.at("per_part.right_palm.thrown"), 3);
  EXPECT_EQ(flat.at("versions.somasim"), "0.1.0");
  EXPECT_EQ(flat.at("seed"), 4);
  EXPECT_EQ(flat.count("ids"), 0u);
  EXPECT_EQ(flat.count("nodes"), 0u);
}

// A node named like another node's metric, and a metric with a '.': names stay distinct.
TEST(MetricsLayout, NamesThatWouldMeetAfterFlatteningAreQualified) {
  const auto m = nlohmann::json::parse(
      R"({"status": "completed", "nodes": {"a": {"b": 1}, "c": {"b": 2, "a": {"b": 3}},
          "x": {"y.z": 4}, "y": {"z": 5}}})");
  std::map<std::string, nlohmann::json> flat;
  for (const auto& [name, value] : flatten_metrics(m)) {
    EXPECT_TRUE(flat.emplace(name, value).second) << name << " twice";
    EXPECT_EQ(find_metric(m, name), value) << name;
  }
  EXPECT_EQ(flat.at("a.b"), 1);
  EXPECT_EQ(flat.at("c.b"), 2);
  EXPECT_EQ(flat.at("c.a.b"), 3);
  EXPECT_EQ(flat.at("y.z"), 4);  // x's metric "y.z" (node y's "z" stays "z")
  EXPECT_EQ(flat.at("z"), 5);
}

// Generated sections: random nodes reporting names from a small pool (so that names clash,
// node names among them), some nested. Every leaf must come out exactly once under a distinct flat
// name, and be found again under it.
TEST(MetricsLayout, GeneratedSectionsFlattenToDistinctNamesThatAreFoundAgain) {
  const std::vector<std::string> pool = {"a", "b", "n0", "n1", "steps", "status", "seed", "nodes"};
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    nlohmann::json m = {{"experiment", "e"}, {"status", "completed"}, {"seed", trial}};
    int leaves = 0;
    const int node_count = 1 + static_cast<int>(rng() % 4);
    for (int n = 0; n < node_count; ++n) {
      nlohmann::json section = nlohmann::json::object();
      for (const auto& name : pool) {
        if (rng() % 2) continue;
        if (rng() % 3 == 0) {
          section[name] = {{"p", static_cast<int>(rng() % 100)}, {"q", {{"r", true}}}};
          leaves += 2;
        } else {
          section[name] = static_cast<int>(rng() % 100);
          ++leaves;
        }
      }
      std::string node = "n";
      node += std::to_string(n);
      m["nodes"][node] = section;
    }
    const auto flat = flatten_metrics(m);
    std::set<std::string> names;
    int node_leaves = 0;
    for (const auto& [name, value] : flat) {
      EXPECT_TRUE(names.insert(name).second) << name << " twice in " << m.dump();
      const auto found = find_metric(m, name);
      ASSERT_TRUE(found.has_value()) << name << " in " << m.dump();
      EXPECT_EQ(*found, value) << name;
      if (name != "experiment" && name != "status" && name != "seed") ++node_leaves;
    }
    EXPECT_EQ(node_leaves, leaves) << m.dump();
  }
}

}  // namespace
}  // namespace somasim
