// configs/pps_learn_visual_objects.yaml, shortened to six objects (three per part): the objects
// are seen by both eyes, tracked (optical flow, CamShift, stereo, Kalman) and teach the learner;
// the neck and eyes follow the tracked object and look between the skin parts when nothing is
// tracked, from the tracker's stimulus and the believed taxels only (never the thrower's truth).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <string>

#include "experiment_runner.hpp"

using somasim::testing::run_config;

namespace {

const std::vector<somasim::Override> kShort = {{"nodes.thrower.params.approaches", "6"}};

// The inputs of node `node` in a resolved experiment file: input name -> source.
std::map<std::string, std::string> node_inputs(const std::filesystem::path& resolved,
                                               const std::string& node) {
  std::map<std::string, std::string> out;
  for (const auto& input : YAML::LoadFile(resolved.string())["nodes"][node]["inputs"])
    out[input.first.as<std::string>()] = input.second.as<std::string>();
  return out;
}

nlohmann::json without_wall_clock(nlohmann::json m) {
  for (const char* key : {"wall_time_s", "real_time_factor"}) m.erase(key);
  return m;
}

}  // namespace

// Measured with seed 1 (six objects, the head following the objects): 77 % of the frames with the
// object in view of both eyes tracked (49 % of all its frames), 2.5 cm RMS position and 2.5 cm/s
// RMS velocity error against the thrower's truth, no fix while no object is present; the gaze on
// a tracked object for 174 steps and home 3 times. Six objects are a small sample of the in-view
// share: 70 % once palm paths keep clear of the thumb (other draws), 74-76 % over 200 objects at
// seeds 1-3. The bounds leave a margin; a tracker stuck on static clutter (the state before the
// motion-consistency checks: 3 % tracked) fails them.
TEST(PpsLearnVisualObjects, ObjectsSeenByTheEyesAreTrackedAndTeachTheLearner) {
  const auto run = run_config("pps_learn_visual_objects", kShort, "a");
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  const auto& track = run.metrics["nodes"]["track"];
  EXPECT_GT(track["frames_in_view"].get<int>(), 100);
  EXPECT_GT(track["in_view_tracked_share"].get<double>(), 0.6);
  EXPECT_GT(track["object_tracked_share"].get<double>(), 0.3);
  EXPECT_LT(track["position_rms_m"].get<double>(), 0.035);
  EXPECT_LT(track["velocity_rms_m_s"].get<double>(), 0.04);
  // False fixes (a fix while no object is present): at most 1 %
  // of the tracked frames.
  EXPECT_LE(track["false_fixes"].get<double>(), 0.01 * track["frames_tracked"].get<double>());
  EXPECT_GT(run.metrics["nodes"]["pps"]["events"].get<int>(), 0);
  // The gaze followed the tracked object and went home (idle) between objects ...
  const auto& gaze = run.metrics["nodes"]["gaze"];
  EXPECT_GT(gaze["steps_with_target"].get<int>(), 50);
  EXPECT_GE(gaze["idle_entries"].get<int>(), 2);
  // ... from the tracker's stimulus and the believed body: the thrower's truth is not its input.
  EXPECT_EQ(node_inputs(run.dir / "experiment.resolved.yaml", "gaze"),
            (std::map<std::string, std::string>{{"target", "track.stimulus"},
                                                {"joint_state", "world.joint_state"},
                                                {"taxels", "believed.taxels"}}));

  // Same seed: the same metrics but for wall-clock figures.
  const auto again = run_config("pps_learn_visual_objects", kShort, "b");
  ASSERT_EQ(again.metrics["status"], "completed") << again.metrics["error"];
  EXPECT_EQ(without_wall_clock(again.metrics), without_wall_clock(run.metrics));
}
