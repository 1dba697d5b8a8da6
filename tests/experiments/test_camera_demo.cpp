// configs/camera_demo.yaml, shortened: the eyes render while the right hand rises in front of
// them and a ball flies at the left forearm; frames and the contact sheet are written.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "experiment_runner.hpp"
#include "somasim/robot/robot_loader.hpp"

using somasim::testing::run_config;

TEST(CameraDemo, WritesStereoFramesAndTheContactSheet) {
  const auto run = run_config("camera_demo", {{"duration_s", "1.2"},
                                              {"nodes.thrower.params.throws", "1"},
                                              {"nodes.cam.params.sheet_times", "[0.2, 1.0]"}});
  ASSERT_EQ(run.metrics["status"], "completed") << run.metrics["error"];
  // 25 Hz over 1.2 s; every 5th frame saved: 1, 6, ..., 26 (t = 1.0 s).
  for (const char* port : {"left_eye_rgb", "right_eye_rgb", "left_eye_depth", "right_eye_depth",
                           "left_eye_mask", "right_eye_mask"})
    for (const char* frame : {"000001.png", "000026.png"})
      EXPECT_TRUE(
          std::filesystem::exists(run.dir / "frames" / (std::string("cam.") + port) / frame))
          << port << " " << frame;
  EXPECT_FALSE(std::filesystem::exists(run.dir / "frames/cam.left_eye_rgb/000002.png"));
  // At t = 1.0 s the right hand is at its first posture before the eyes: both masks see it.
  const auto model =
      somasim::robot::load_robot_model(SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml");
  const int hand_id = model.link_index("r_hand") + 1;
  for (const char* eye : {"left_eye", "right_eye"}) {
    const cv::Mat mask = cv::imread(
        (run.dir / "frames" / (std::string("cam.") + eye + "_mask") / "000026.png").string(),
        cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_16U);
    EXPECT_GT(cv::countNonZero(mask == hand_id), 1000) << eye;
  }
  const cv::Mat sheet = cv::imread((run.dir / "figures/stereo_frames.png").string());
  EXPECT_EQ(sheet.cols, 2 * (320 + 4) + 4);
  // Two rows of frames under a line of camera names.
  EXPECT_GT(sheet.rows, 2 * (240 + 4) + 10);
  EXPECT_LT(sheet.rows, 2 * (240 + 4) + 40);
  EXPECT_TRUE(std::filesystem::exists(run.dir / "figures/stereo_frames.svg"));
}
