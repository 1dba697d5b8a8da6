// configs/pps_scale.yaml, shortened to 25 s of simulated time: the 4,245-taxel whole-arm and
// torso skin learns from objects approaching every part, with the robot locked (static
// geometry that the kinematic objects touch), and the run reports its real-time factor.
#include <gtest/gtest.h>

#include "experiment_runner.hpp"

using somasim::testing::read_file;
using somasim::testing::run_config;

namespace {
const char* const kParts[] = {"left_upper_arm", "right_upper_arm", "left_forearm", "right_forearm",
                              "left_palm",      "right_palm",      "torso"};
}

TEST(PpsScale, EveryPartOfTheWholeArmSkinLearnsWithTheWorldAt1kHz) {
  const auto run = run_config("pps_scale", {{"duration_s", "25"}});
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_DOUBLE_EQ(run.metrics["sim_time_s"].get<double>(), 25.0);
  const auto& pps = run.metrics["nodes"]["pps"];
  int taxels = 0;
  for (const char* part : kParts) {
    const auto& p = pps["per_part"][part];
    taxels += p["taxels"].get<int>();
    EXPECT_GE(p["events"].get<int>(), 1) << part;  // one approach per part, in turn
    EXPECT_GT(p["positive_samples"].get<int>(), 0) << part;
  }
  EXPECT_GE(taxels, 4000);
  EXPECT_EQ(run.metrics["nodes"]["skin"]["events_total"], pps["events"]);
  EXPECT_GT(run.metrics["real_time_factor"].get<double>(), 0.0);
  EXPECT_FALSE(read_file(run.dir / "pps_full_skin.json").empty());
}

TEST(PpsScale, SameSeedSameLearnedSkin) {
  const std::vector<somasim::Override> shorter = {{"duration_s", "8"}};
  const auto a = run_config("pps_scale", shorter, "a");
  const auto b = run_config("pps_scale", shorter, "b");
  ASSERT_EQ(a.metrics["status"], "completed") << a.metrics["error"];
  EXPECT_GE(a.metrics["nodes"]["pps"]["events"].get<int>(), 1);
  EXPECT_EQ(read_file(a.dir / "pps_full_skin.json"), read_file(b.dir / "pps_full_skin.json"));
  EXPECT_EQ(read_file(a.dir / "pps.max_activation.csv"),
            read_file(b.dir / "pps.max_activation.csv"));
}
