#include <gtest/gtest.h>

#include <filesystem>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

// configs/pps_learn_double_touch.yaml, shortened to three touches: in the physics world the
// fingertip reaches the left forearm's skin every time and nowhere else, the learner learns
// from the events and compares its offsets with the true ones.
TEST(PpsLearnDoubleTouch, FingertipTouchesTeachTheForearm) {
  const std::vector<somasim::Override> shorter = {{"nodes.touch.params.touches", "3"}};
  const auto run = run_config("pps_learn_double_touch", shorter, "a");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& touch = run.metrics["nodes"]["touch"];
  EXPECT_EQ(touch["touches"], 3);
  EXPECT_EQ(touch["touches_reached_skin"], 3);
  EXPECT_EQ(touch["touches_on_aimed_taxel"], 3);
  EXPECT_EQ(touch["events_elsewhere"], 0);
  EXPECT_EQ(touch["events_outside_touches"], 0);
  EXPECT_LT(touch["final_error_max_m"].get<double>(), 0.005);
  EXPECT_GT(touch["true_offset_samples"].get<int>(), 0);
  const auto& pps = run.metrics["nodes"]["pps"];
  EXPECT_EQ(pps["events"], 3);
  EXPECT_GT(pps["positive_samples"].get<int>(), 0);
  EXPECT_TRUE(pps.contains("offset_error_max_m"));
  EXPECT_TRUE(std::filesystem::exists(run.dir / "pps_double_touch.json"));
  EXPECT_TRUE(
      std::filesystem::exists(run.dir / "figures/landscape_left_forearm_13_after_1_events.png"));

  // Same seed: the same touches and the same learning.
  const auto again = run_config("pps_learn_double_touch", shorter, "b");
  EXPECT_EQ(again.metrics["nodes"]["touch"].dump(), touch.dump());
  EXPECT_EQ(again.metrics["nodes"]["pps"].dump(), pps.dump());
}

// Double touch with kinematic errors of either sign: every evaluated taxel's contact estimate
// within 1 cm of the truth (the README's offset table reports the full runs).
class PpsLearnDoubleTouchErrorSets : public ::testing::TestWithParam<const char*> {};

TEST_P(PpsLearnDoubleTouchErrorSets, EveryTaxelEstimateWithinOneCentimetre) {
  const std::vector<somasim::Override> overrides = {
      {"nodes.touch.params.touches", "25"},
      {"nodes.believed.params.joint_offsets_deg", std::string("{") + GetParam() + "}"}};
  const auto run = run_config("pps_learn_double_touch", overrides, "set");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  EXPECT_GE(run.metric("offset_taxels_evaluated").get<int>(), 5);
  EXPECT_LE(run.metric("offset_error_max_m").get<double>(), 0.01) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(
    Sets, PpsLearnDoubleTouchErrorSets,
    ::testing::Values(
        "l_elbow: 4, l_wrist_prosup: 3, r_elbow: -3, r_wrist_pitch: -4, r_wrist_yaw: 3",
        "l_elbow: -4, l_wrist_prosup: -3, r_elbow: 3, r_wrist_pitch: 4, r_wrist_yaw: -3"));
