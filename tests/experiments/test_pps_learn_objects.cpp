#include <gtest/gtest.h>

#include <filesystem>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

// configs/pps_learn_objects.yaml, shortened: objects reach the skin, the skin reports the
// contacts and both parts learn (the experiment's offset metrics are work in progress).
TEST(PpsLearnObjects, ApproachingObjectsTeachBothParts) {
  const auto run = run_config("pps_learn_objects", {{"nodes.thrower.params.approaches", "4"}});
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_EQ(run.metrics["approaches"], 4);
  EXPECT_EQ(run.metrics["nodes"]["pps_forearm"]["events"], 2);
  EXPECT_EQ(run.metrics["nodes"]["pps_palm"]["events"], 2);
  EXPECT_GT(run.metrics["nodes"]["pps_forearm"]["positive_samples"].get<int>(), 0);
  EXPECT_TRUE(std::filesystem::exists(run.dir / "pps_left_forearm.json"));
  // Fig 9-style snapshot after the first event, and the final landscapes.
  EXPECT_TRUE(
      std::filesystem::exists(run.dir / "figures/landscape_left_forearm_0_after_1_events.png"));
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/landscape_right_palm_0.png"));
}
