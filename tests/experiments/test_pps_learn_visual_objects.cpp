// configs/pps_learn_visual_objects.yaml, shortened to six objects (three per part): the objects
// are seen by both eyes, tracked (optical flow, CamShift, stereo, Kalman) and teach the learner.
#include <gtest/gtest.h>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

namespace {

const std::vector<somasim::Override> kShort = {{"nodes.thrower.params.approaches", "6"}};

nlohmann::json without_wall_clock(nlohmann::json m) {
  for (const char* key : {"wall_time_s", "real_time_factor"}) m.erase(key);
  return m;
}

}  // namespace

// Measured with seed 1 (six objects): 76 % of the frames with the object in view of both eyes
// tracked (39 % of all its frames), 1.9 cm RMS position and 1.7 cm/s RMS velocity error against
// the thrower's truth, no fix while no object is present. The bounds leave a margin; a tracker
// stuck on static clutter (the state before the motion-consistency checks: 3 % tracked) fails them.
TEST(PpsLearnVisualObjects, ObjectsSeenByTheEyesAreTrackedAndTeachTheLearner) {
  const auto run = run_config("pps_learn_visual_objects", kShort, "a");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& track = run.metrics["nodes"]["track"];
  EXPECT_GT(track["frames_in_view"].get<int>(), 100);
  EXPECT_GT(track["in_view_tracked_share"].get<double>(), 0.7);
  EXPECT_GT(track["object_tracked_share"].get<double>(), 0.3);
  EXPECT_LT(track["position_rms_m"].get<double>(), 0.035);
  EXPECT_LT(track["velocity_rms_m_s"].get<double>(), 0.04);
  EXPECT_EQ(track["false_fixes"], 0);
  EXPECT_GT(run.metrics["nodes"]["pps"]["events"].get<int>(), 0);

  // Same seed: the same metrics but for wall-clock figures.
  const auto again = run_config("pps_learn_visual_objects", kShort, "b");
  ASSERT_EQ(again.metrics["status"], "completed") << again.metrics["error"];
  EXPECT_EQ(without_wall_clock(again.metrics), without_wall_clock(run.metrics));
}
