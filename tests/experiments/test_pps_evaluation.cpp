#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "experiment_runner.hpp"

using somasim::testing::read_file;
using somasim::testing::run_config;

// configs/pps_avoidance.yaml and pps_reaching.yaml, shortened: a map is learned first
// (configs/pps_learn_objects.yaml, 40 objects), then 7 objects are presented (5 approaches, one
// static, one receding, cylinders not used in learning) with the controllers in the loop.
namespace {

const std::filesystem::path& learned_map() {
  static const std::filesystem::path file = [] {
    const auto run = run_config("pps_learn_objects", {{"nodes.thrower.params.approaches", "40"},
                                                      {"nodes.pps.params.save", "learned.json"},
                                                      {"nodes.pps.params.snapshot_events", "[]"}});
    EXPECT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
    return run.dir / "learned.json";
  }();
  return file;
}

somasim::testing::ExperimentRun evaluate(const std::string& config, const std::string& tag) {
  return run_config(
      config,
      {{"nodes.pps.params.load", learned_map().string()}, {"nodes.thrower.params.approaches", "7"}},
      tag);
}

void expect_rate(const nlohmann::json& v, const std::string& key) {
  ASSERT_TRUE(v.is_number()) << key << ": " << v;
  EXPECT_GE(v.get<double>(), 0.0) << key;
  EXPECT_LE(v.get<double>(), 1.0) << key;
}

}  // namespace

TEST(PpsEvaluation, AvoidanceScoresEveryPresentation) {
  ASSERT_TRUE(std::filesystem::exists(learned_map()));
  const auto run = evaluate("pps_avoidance", "a");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& m = run.metrics["nodes"]["eval"];
  for (const char* key : {"approaches", "triggered_rate", "skin_contact_rate", "contact_rate",
                          "min_distance_m", "trigger_distance_m", "false_trigger_rate"})
    EXPECT_TRUE(run.flat.contains(key)) << key;  // by their flat names
  EXPECT_EQ(run.metric("approaches"), 5);
  EXPECT_EQ(m["approaches"], 5);
  EXPECT_EQ(m["presentations"], 7);
  for (const char* k :
       {"triggered_rate", "skin_contact_rate", "contact_rate", "false_trigger_rate"})
    expect_rate(m[k], k);
  EXPECT_GT(m["triggered_rate"].get<double>(), 0.0);  // the learned map announces objects
  EXPECT_EQ(m["min_distance_m"]["n"], 5);
  EXPECT_EQ(m["trigger_distance_m"]["n"].get<int>(),
            static_cast<int>(std::lround(5 * m["triggered_rate"].get<double>())));
  // (D, TTC) with the signed TTC: a static or receding object has no time to contact.
  EXPECT_EQ(m["static_trigger_rate"], 0.0);
  EXPECT_EQ(m["receding_trigger_rate"], 0.0);
  EXPECT_GT(run.metrics["nodes"]["avoid_left"]["triggers"].get<int>() +
                run.metrics["nodes"]["avoid_right"]["triggers"].get<int>(),
            0);
  // One CSV row per presentation; the chosen presentations are drawn.
  const std::string csv = read_file(run.dir / "presentations.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8);
  EXPECT_TRUE(
      std::filesystem::exists(run.dir / "figures/presentation_1_approach_left_forearm.png"));
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/presentation_6_static_right_palm.png"));
  // Same seed, same outputs.
  const auto again = evaluate("pps_avoidance", "b");
  EXPECT_EQ(read_file(again.dir / "presentations.csv"), csv);
}

TEST(PpsEvaluation, ReachingScoresContacts) {
  const auto run = evaluate("pps_reaching", "r");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& m = run.metrics["nodes"]["eval"];
  EXPECT_EQ(m["approaches"], 5);
  expect_rate(m["contact_rate"], "contact_rate");
  EXPECT_EQ(m["receding_trigger_rate"], 0.0);
}
