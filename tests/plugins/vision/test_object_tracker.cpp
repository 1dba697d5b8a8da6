// The `object_tracker` plugin through the public harness: its bad-input errors (a camera not in
// the robot model, images of another size than the camera's calibration), a track only one
// eye has dropped after unfixed_frames_lost, the velocity checks, and the per-frame trace.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "somasim/error.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"

using somasim::Image;
using somasim::JointState;
using somasim::RgbImage;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

std::string graph(const std::string& params = "") {
  return "seed: 1\nbase_rate_hz: 20\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  track:\n    plugin: object_tracker\n    params: {" + params +
         "}\n    inputs: {left_eye_rgb: harness.left, right_eye_rgb: harness.right, "
         "joint_state: harness.q}\n";
}

}  // namespace

TEST(ObjectTracker, CameraNotInTheRobotModelIsAClearError) {
  try {
    Harness h(graph("cameras: [left_eye, nose]"));
    FAIL() << "no error";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:23: node 'track', key 'params.cameras': camera 'nose' is not in robot "
                 "'icub_v1' (cameras: left_eye, right_eye)");
  }
}

TEST(ObjectTracker, ImagesOfAnotherSizeThanTheCalibrationAreARunError) {
  Harness h(graph());
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  h.input<JointState>("q").position = Eigen::VectorXd::Zero(model->num_dofs());
  for (const char* eye : {"left", "right"}) {
    Image& image = h.input<RgbImage>(eye);
    image.data = cv::Mat(480, 640, CV_8UC3, cv::Scalar(0, 0, 0));
    image.encoding = somasim::ImageEncoding::kRgb8;
    image.camera = std::string(eye) + "_eye";
    image.frame = 1;
  }
  try {
    h.step(1);
    FAIL() << "no error";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "input 'left_eye_rgb': the image is 640 × 480 px, but camera 'left_eye' of "
                 "robot 'icub_v1' is calibrated for 320 × 240 px (wire images of that camera at "
                 "its resolution)");
  }
}

namespace {

// Feeds `frames` frames of 320 x 240 to both eyes: a green chequered square (texture for the
// optical flow) of `left_px` / `right_px` side (0: none, grey) moving right 3 px a frame and
// growing by `growth_px` a frame; the robot at rest; the right eye's square `disparity_px` left
// of the left eye's. Returns the tracker's metric `name`; `inspect` (if any) sees the harness
// after the run.
std::int64_t squares_metric(const std::string& params, const std::string& name, int frames,
                            int left_px, int right_px, int disparity_px = 0, int growth_px = 0,
                            const std::function<void(const Harness&)>& inspect = nullptr) {
  // (The squares' green is one of the robot's own colours: not refused here.)
  Harness h(graph("refuse_own_colours: false" + (params.empty() ? "" : ", " + params)));
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  h.input<JointState>("q").position = Eigen::VectorXd::Zero(model->num_dofs());
  for (int f = 1; f <= frames; ++f) {
    for (const char* eye : {"left", "right"}) {
      Image& image = h.input<RgbImage>(eye);
      image.data = cv::Mat(240, 320, CV_8UC3, cv::Scalar(110, 110, 110));
      const bool left = std::string(eye) == "left";
      const int side = (left ? left_px : right_px) + (f - 1) * growth_px;
      const int column = 60 + 3 * f - (left ? 0 : disparity_px);
      for (int r = 0; r < side; ++r)
        for (int c = 0; c < side; ++c)
          image.data.at<cv::Vec3b>(100 + r, column + c) =
              (r / 5 + c / 5) % 2 ? cv::Vec3b(30, 170, 40) : cv::Vec3b(20, 120, 30);
      image.encoding = somasim::ImageEncoding::kRgb8;
      image.camera = std::string(eye) + "_eye";
      image.frame = static_cast<std::uint64_t>(f);
      image.time_s = h.time_s();
    }
    h.step(1);
  }
  h.finish();
  if (inspect) inspect(h);
  return h.metric("track", name).get<std::int64_t>();
}

// The fields of each line of a CSV file (no quoting), the header first.
std::vector<std::vector<std::string>> csv_rows(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string>& row = rows.emplace_back();
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(f);
    if (!line.empty() && line.back() == ',') row.emplace_back();
  }
  return rows;
}

}  // namespace

// With a trace file: one row per frame, every row as wide as the header; the frames whose
// outcome is "fixed" are the tracked frames, those fixed without their velocity the withheld
// ones; a track seen by one eye only reads left_only. Without the parameter no file is written.
TEST(ObjectTracker, TheTraceHasARowPerFrameThatAgreesWithTheMetrics) {
  const std::string params =
      "unfixed_frames_lost: 1000, max_velocity_sigma: 0.1, trace: track_trace.csv";
  constexpr int kFrames = 30, kDisparity = 40;
  std::int64_t tracked = 0, withheld = 0;
  std::vector<std::vector<std::string>> rows;
  squares_metric(params, "frames", kFrames, 30, 30, kDisparity, 0, [&](const Harness& h) {
    rows = csv_rows(h.out_dir() / "track_trace.csv");
    tracked = h.metric("track", "frames_tracked").get<std::int64_t>();
    withheld = h.metric("track", "velocity_withheld_frames").get<std::int64_t>();
  });
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kFrames) + 1);
  const std::vector<std::string>& header = rows.front();
  ASSERT_EQ(header[1], "outcome");
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t reported = column("velocity_reported");
  ASSERT_LT(reported, header.size());
  std::int64_t fixed = 0, fixed_without_velocity = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), header.size()) << "row " << k;
    const bool is_fixed = rows[k][1] == "fixed";
    fixed += is_fixed ? 1 : 0;
    fixed_without_velocity += is_fixed && rows[k][reported] == "0" ? 1 : 0;
  }
  EXPECT_GT(tracked, 10);
  EXPECT_EQ(fixed, tracked);
  EXPECT_EQ(fixed_without_velocity, withheld);
  EXPECT_GT(withheld, 0);

  bool written = true;
  squares_metric("", "frames", kFrames, 30, 0, 0, 0, [&](const Harness& h) {
    written = std::filesystem::exists(h.out_dir() / "track_trace.csv");
  });
  EXPECT_FALSE(written);
  std::int64_t left_only = 0;
  squares_metric("trace: t.csv", "frames", kFrames, 30, 0, 0, 0, [&](const Harness& h) {
    const auto one_eye = csv_rows(h.out_dir() / "t.csv");
    left_only = std::count_if(std::next(one_eye.begin()), one_eye.end(),
                              [](const auto& r) { return r[1] == "left_only"; });
  });
  EXPECT_GT(left_only, kFrames / 2);
}

// An object only one eye sees gives no stereo fix; its track is dropped every
// unfixed_frames_lost frames (and re-acquired by motion), so that a track left on clutter cannot
// keep that eye from acquiring the next object. Without the drop the track is kept throughout.
TEST(ObjectTracker, AOneEyedTrackIsDroppedAfterUnfixedFramesLost) {
  EXPECT_EQ(squares_metric("", "frames_tracked", 40, 30, 0), 0);
  EXPECT_GT(squares_metric("", "acquisitions", 40, 30, 0), 0);
  EXPECT_GE(squares_metric("unfixed_frames_lost: 10", "unfixed_drops", 40, 30, 0), 2);
  EXPECT_EQ(squares_metric("unfixed_frames_lost: 1000", "unfixed_drops", 40, 30, 0), 0);
}

// With max_velocity_sigma the first fixes of a track, whose velocity the Kalman filter does not
// yet know, are reported with velocity 0 and counted: a few after the acquisition, all of them
// for a bound below the filter's steady state, none without the option.
TEST(ObjectTracker, AFixWhoseVelocityIsNotYetKnownIsReportedWithoutIt) {
  const std::string keep = "unfixed_frames_lost: 1000";
  constexpr int kDisparity = 40;  // [px]: about 0.4 m in front of the eyes
  const std::int64_t tracked = squares_metric(keep, "frames_tracked", 30, 30, 30, kDisparity);
  ASSERT_GT(tracked, 10);
  EXPECT_EQ(squares_metric(keep, "velocity_withheld_frames", 30, 30, 30, kDisparity), 0);
  const std::int64_t first = squares_metric(keep + ", max_velocity_sigma: 0.1",
                                            "velocity_withheld_frames", 30, 30, 30, kDisparity);
  EXPECT_GE(first, 3);
  EXPECT_LE(first, 8);
  EXPECT_EQ(squares_metric(keep + ", max_velocity_sigma: 0.001", "velocity_withheld_frames", 30, 30,
                           30, kDisparity),
            tracked);
}

// With max_velocity_disagreement a fix's velocity is reported only where the track's last
// velocity_window_fixes fixes show it: with a tolerance no noise meets, every fix is withheld and
// counted as disputed; with a loose one only a new track's first fixes (too few for the window);
// without the option none.
TEST(ObjectTracker, AVelocityTheTracksFixesDoNotShowIsReportedWithoutIt) {
  const std::string keep = "unfixed_frames_lost: 1000";
  constexpr int kDisparity = 40;  // [px]
  const std::int64_t tracked = squares_metric(keep, "frames_tracked", 30, 30, 30, kDisparity);
  ASSERT_GT(tracked, 10);
  EXPECT_EQ(squares_metric(keep, "velocity_disputed_frames", 30, 30, 30, kDisparity), 0);
  EXPECT_EQ(squares_metric(keep + ", max_velocity_disagreement: 1e-9", "velocity_disputed_frames",
                           30, 30, 30, kDisparity),
            tracked);
  for (const int fixes : {3, 6}) {
    const std::string loose =
        keep + ", max_velocity_disagreement: 10, velocity_window_fixes: " + std::to_string(fixes);
    const std::int64_t first =
        squares_metric(loose, "velocity_disputed_frames", 30, 30, 30, kDisparity);
    EXPECT_GE(first, fixes - 1) << fixes;
    EXPECT_LE(first, 2 * (fixes - 1)) << fixes;  // at most one reset
    EXPECT_EQ(squares_metric(loose, "velocity_withheld_frames", 30, 30, 30, kDisparity), first);
  }
}

// With max_radius_rate a fix whose track's radius (from area and depth) is still changing is
// reported without velocity and counted: every fix of a square that grows 1 px a frame (its
// radius 0.4-0.7 of itself a second), only a new track's first fixes (too few for the window) of
// one that keeps its size, none without the option.
TEST(ObjectTracker, AVelocityOfATrackWhoseRadiusIsStillChangingIsReportedWithoutIt) {
  const std::string keep = "unfixed_frames_lost: 1000";
  constexpr int kDisparity = 40;  // [px]
  for (const int growth : {0, 1}) {
    const std::int64_t tracked =
        squares_metric(keep, "frames_tracked", 30, 30, 30, kDisparity, growth);
    ASSERT_GT(tracked, 10) << growth;
    EXPECT_EQ(squares_metric(keep, "radius_unsettled_frames", 30, 30, 30, kDisparity, growth), 0);
    const std::string gated = keep + ", max_radius_rate: 0.3";
    const std::int64_t unsettled =
        squares_metric(gated, "radius_unsettled_frames", 30, 30, 30, kDisparity, growth);
    if (growth == 0) {
      EXPECT_GE(unsettled, 4);
      EXPECT_LE(unsettled, 8);  // at most one reset
    } else {
      EXPECT_EQ(unsettled, tracked);
    }
    EXPECT_EQ(squares_metric(gated, "velocity_withheld_frames", 30, 30, 30, kDisparity, growth),
              unsettled);
  }
}

// With velocity_over_settling a fix is reported without velocity where its speed is no more than
// that multiple of the speed at which its track's radius changes: a square moving 3 px a frame
// (about 0.09 m/s) and growing 1 px a frame (its radius about 0.01 m/s) keeps its velocity at a
// factor of 2 and loses it at 20 on nearly every fix; one that keeps its size keeps it at 20;
// without the option nothing is withheld.
TEST(ObjectTracker, AVelocityTheWindowsOwnGrowthExplainsIsReportedWithoutIt) {
  const std::string keep = "unfixed_frames_lost: 1000";
  constexpr int kDisparity = 40;  // [px]
  const auto settling = [&](const std::string& factor, int growth) {
    return squares_metric(keep + (factor.empty() ? "" : ", velocity_over_settling: " + factor),
                          "velocity_settling_frames", 30, 30, 30, kDisparity, growth);
  };
  const std::int64_t tracked = squares_metric(keep, "frames_tracked", 30, 30, 30, kDisparity, 1);
  ASSERT_GT(tracked, 10);
  EXPECT_EQ(settling("", 1), 0);
  EXPECT_EQ(settling("2", 1), 0);
  EXPECT_GE(settling("20", 1), tracked - 3);
  EXPECT_EQ(settling("20", 0), 0);
  EXPECT_EQ(squares_metric(keep + ", velocity_over_settling: 20", "velocity_withheld_frames", 30,
                           30, 30, kDisparity, 1),
            settling("20", 1));
}

// Two tracks of unlike areas (over 3 : 1) are not one object: the smaller is dropped at once and
// its eye re-acquires by motion. Like areas are kept.
TEST(ObjectTracker, OfTwoTracksOfUnlikeAreasTheSmallerIsDropped) {
  EXPECT_GT(squares_metric("unfixed_frames_lost: 1000", "area_drops", 30, 12, 40), 0);
  EXPECT_EQ(squares_metric("unfixed_frames_lost: 1000", "area_drops", 30, 30, 30), 0);
}

// With max_size_ratio two tracks whose sizes at the triangulated depth differ by more than that
// ratio give no fix (metric size_mismatches): squares of 30 and 40 px side (within the 3 : 1
// area check) are never fixed at 1.25 and fixed in most frames without the check; two of like
// size are fixed with it.
TEST(ObjectTracker, TwoTracksOfUnlikeSizesAtTheirDepthGiveNoFix) {
  const std::string keep = "unfixed_frames_lost: 1000";
  const std::string checked = keep + ", max_size_ratio: 1.25";
  constexpr int kDisparity = 40;  // [px]
  EXPECT_EQ(squares_metric(checked, "frames_tracked", 30, 30, 40, kDisparity), 0);
  EXPECT_GT(squares_metric(checked, "size_mismatches", 30, 30, 40, kDisparity), 10);
  EXPECT_GT(squares_metric(keep, "frames_tracked", 30, 30, 40, kDisparity), 10);
  EXPECT_EQ(squares_metric(keep, "size_mismatches", 30, 30, 40, kDisparity), 0);
  EXPECT_GT(squares_metric(checked, "frames_tracked", 30, 30, 30, kDisparity), 10);
  EXPECT_EQ(squares_metric(checked, "size_mismatches", 30, 30, 30, kDisparity), 0);
}
