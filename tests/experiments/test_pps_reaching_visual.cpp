// configs/pps_reaching_visual.yaml, shortened to seven objects (five approaches, one static, one
// receding): the objects seen by the eyes drive the reaching controllers; after an object met by
// an arm is withdrawn, the tracker does not take the withdrawing hand (the robot's own colour)
// for the object.
#include <gtest/gtest.h>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

// Measured with seed 1 (seven objects): no false fix, 144 acquisitions of the robot's own colours
// refused, the gaze on a tracked object for 75 steps, contact with both right-palm approaches;
// with objects presented where both eyes see them coming, contact with all 5 approaches.
// With refuse_own_colours: false the tracker, and the eyes with it, followed the withdrawing hand:
// 203 false fixes, 30 cm RMS position error. The bounds leave a margin.
TEST(PpsReachingVisual, ObjectsSeenByTheEyesAreReachedAndTheHandIsNoObject) {
  const auto run = run_config("pps_reaching_visual", {{"nodes.thrower.params.approaches", "7"}});
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& track = run.metrics["nodes"]["track"];
  EXPECT_GT(track["frames_in_view"].get<int>(), 100);
  EXPECT_GT(track["own_colour_refusals"].get<int>(), 0);
  EXPECT_LE(track["false_fixes"].get<int>(), 3);
  EXPECT_GT(run.metrics["nodes"]["gaze"]["steps_with_target"].get<int>(), 20);
  const auto& eval = run.metrics["nodes"]["eval"];
  EXPECT_EQ(eval["approaches"], 5);
  EXPECT_GE(eval["per_part"]["right_palm"]["contact_rate"].get<double>(), 0.5);
  EXPECT_GE(eval["contact_rate"].get<double>(), 0.8);
}
