// The `marker_tracker` plugin through the public harness, fed by the `camera` plugin's renders
// of the iCub: the tracked green fingertip marker against the true r_index_tip frame (position,
// pixels, velocity), and its bad-input errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "somasim/error.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"
#include "somasim/units.hpp"
#include "somasim/vision/ports.hpp"

using somasim::Image;
using somasim::JointState;
using somasim::LinkPoses;
using somasim::RgbImage;
using somasim::StereoPixels;
using somasim::pps::Stimulus;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

const somasim::robot::RobotModel& model() {
  static const auto m = somasim::robot::load_robot_model_shared(kRobot);
  return *m;
}

// Camera `cam` renders the true link poses (harness.links); `track` sees its images and the
// encoders (harness.q).
std::string graph(const std::string& params = "", const std::string& camera_params = "",
                  int seed = 1, const std::string& extra_inputs = "") {
  return "seed: " + std::to_string(seed) + "\nbase_rate_hz: 30\nrobots: {icub: " + kRobot +
         "}\nnodes:\n"
         "  cam:\n    plugin: camera\n    params: {outputs: rgb" +
         camera_params +
         "}\n"
         "    inputs: {link_poses: harness.links}\n"
         "  track:\n    plugin: marker_tracker\n    params: {" +
         params +
         "}\n    inputs: {left_eye_rgb: cam.left_eye_rgb, right_eye_rgb: cam.right_eye_rgb, "
         "joint_state: harness.q" +
         extra_inputs + "}\n";
}

// The right hand in front of the eyes, fingertip toward the left (posture [deg]).
std::map<std::string, double> hand_before_eyes() {
  return {{"r_shoulder_pitch", -90},
          {"r_shoulder_roll", 5},
          {"r_shoulder_yaw", 25},
          {"r_elbow", 40},
          {"r_wrist_prosup", 0}};
}

Eigen::VectorXd joints(const std::map<std::string, double>& posture) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model().num_dofs());
  for (const auto& [joint, deg] : posture) q[model().dof_index(joint)] = somasim::deg_to_rad(deg);
  return q;
}

std::vector<Eigen::Isometry3d> link_poses(const Eigen::VectorXd& q) {
  somasim::robot::RobotData data(model());
  somasim::robot::forward_kinematics(model(), data, q);
  return data.link_poses;
}

// Feeds q to both the camera (true link poses) and the tracker (encoders); returns the true
// marker centre (frame r_index_tip, root frame).
Eigen::Vector3d set_posture(Harness& h, const Eigen::VectorXd& q) {
  somasim::robot::RobotData data(model());
  somasim::robot::forward_kinematics(model(), data, q);
  h.input<LinkPoses>("links").poses = data.link_poses;
  h.input<JointState>("q").position = q;
  h.input<JointState>("q").velocity = Eigen::VectorXd::Zero(q.size());
  const auto tip = model().frame_ref("r_index_tip");
  return data.link_poses[static_cast<std::size_t>(tip.link)] * tip.pose.translation();
}

std::string input_error(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(MarkerTracker, PositionAndPixelsMatchTheFingertip) {
  Harness h(graph());
  const Eigen::VectorXd q = joints(hand_before_eyes());
  const Eigen::Vector3d tip = set_posture(h, q);
  h.step(3);
  const auto& s = h.output<Stimulus>("track.stimulus");
  const auto& px = h.output<StereoPixels>("track.marker_pixels");
  ASSERT_TRUE(s.present);
  EXPECT_LT((s.position - tip).norm(), 0.002)
      << s.position.transpose() << " vs " << tip.transpose();
  EXPECT_LT(s.velocity.norm(), 0.01);  // a still hand
  EXPECT_DOUBLE_EQ(s.radius, 0.007);
  const auto data = link_poses(q);
  for (const auto& [eye, camera] :
       {std::pair{&px.left, "left_eye"}, std::pair{&px.right, "right_eye"}}) {
    EXPECT_TRUE(eye->found) << camera;
    EXPECT_GT(eye->area_px, 20) << camera;
    const Eigen::Vector2d truth = *somasim::render::camera_for(model(), camera, data).project(tip);
    EXPECT_LT((eye->circle_px - truth).norm(), 1.0) << camera;
    // The centroid moves toward the visible part of the marker (the finger hides the rest).
    EXPECT_GT((eye->uv_px - truth).norm(), (eye->circle_px - truth).norm()) << camera;
  }
  EXPECT_EQ(px.frame, 3u);
  h.finish();
  EXPECT_EQ(h.metric("track", "frames"), 3);
  EXPECT_EQ(h.metric("track", "tracked_share"), 1.0);
  EXPECT_EQ(h.metric("track", "in_view_tracked_share"), 1.0);
  EXPECT_LT(h.metric("track", "reprojection_max_px").get<double>(), 1.0);
}

// Over 45 wrist postures the marker is partly hidden by its finger and the hand in various
// ways: half the fixes are within 1.5 mm of the fingertip, 80 % within 4 mm, none far off
// (the enclosing circle assumes at most half of the marker hidden).
TEST(MarkerTracker, AcrossWristPosturesMostFixesAreWithinAFewMillimetres) {
  std::vector<double> errors;
  int hidden = 0;
  for (double prosup : {-60.0, -30.0, 0.0, 30.0, 60.0})
    for (double pitch : {-40.0, 0.0, 40.0})
      for (double yaw : {-20.0, 0.0, 20.0}) {
        Harness h(graph());
        auto p = hand_before_eyes();
        p["r_wrist_prosup"] = prosup;
        p["r_wrist_pitch"] = pitch;
        p["r_wrist_yaw"] = yaw;
        const Eigen::Vector3d tip = set_posture(h, joints(p));
        h.step(1);
        const auto& s = h.output<Stimulus>("track.stimulus");
        if (!s.present) {
          ++hidden;
          continue;
        }
        errors.push_back((s.position - tip).norm());
      }
  std::sort(errors.begin(), errors.end());
  ASSERT_GE(errors.size(), 40u);
  EXPECT_LE(hidden, 5);
  std::printf("marker fixes: %zu of 45, error median %.2f mm, 80 %% %.2f mm, max %.2f mm\n",
              errors.size(), 1e3 * errors[errors.size() / 2], 1e3 * errors[errors.size() * 8 / 10],
              1e3 * errors.back());
  EXPECT_LT(errors[errors.size() / 2], 0.0015);      // median
  EXPECT_LT(errors[errors.size() * 8 / 10], 0.004);  // 80 %
  EXPECT_LT(errors.back(), 0.03);
}

// The hand moves at constant joint speeds (the fingertip at about 0.1 m/s, toward the eyes):
// after 10 frames the Kalman velocity follows the fingertip's within 15 % (1 mm of pixel
// noise is 0.04 m/s of raw finite-difference noise at 30 Hz).
TEST(MarkerTracker, VelocityFollowsAMovingHand) {
  Harness h(graph("process_noise: 0.5", "", 1, ", true_link_poses: harness.links"));
  auto p = hand_before_eyes();
  p["r_wrist_pitch"] = 40;
  p["r_wrist_yaw"] = -20;
  const double dt = 1.0 / 30;
  Eigen::Vector3d tip = Eigen::Vector3d::Zero(), previous = tip;
  double error_sum = 0.0, speed_sum = 0.0;
  for (int k = 0; k <= 20; ++k) {
    Eigen::VectorXd q = joints(p);
    q[model().dof_index("r_elbow")] += somasim::deg_to_rad(20.0) * k * dt;  // 20 deg/s
    q[model().dof_index("r_shoulder_yaw")] -= somasim::deg_to_rad(10.0) * k * dt;
    previous = tip;
    tip = set_posture(h, q);
    h.step(1);
    const auto& s = h.output<Stimulus>("track.stimulus");
    ASSERT_TRUE(s.present) << "frame " << k;
    EXPECT_LT((s.position - tip).norm(), 0.003) << "frame " << k;
    if (k >= 10) {
      const Eigen::Vector3d truth = (tip - previous) / dt;  // constant within 1 %
      error_sum += (s.velocity - truth).norm();
      speed_sum += truth.norm();
    }
  }
  std::printf("moving marker: mean speed %.3f m/s, mean velocity error %.3f m/s\n", speed_sum / 11,
              error_sum / 11);
  EXPECT_GT(speed_sum / 11, 0.05);  // [m/s]
  EXPECT_LT(error_sum, 0.15 * speed_sum);
  h.finish();
  EXPECT_EQ(h.metric("track", "tracked_share"), 1.0);
  // The same errors as metrics, against the true link poses.
  const double position_rms = h.metric("track", "position_rms_m").get<double>();
  const double velocity_rms = h.metric("track", "velocity_rms_m_s").get<double>();
  std::printf("metrics: position_rms %.2f mm, velocity_rms %.3f m/s\n", 1e3 * position_rms,
              velocity_rms);
  EXPECT_GT(position_rms, 0.0);
  EXPECT_LT(position_rms, 0.003);
  EXPECT_GT(velocity_rms, 0.0);
  EXPECT_LT(velocity_rms, 0.05);  // the first frames start from velocity 0
}

// With a neck offset the believed eyes are the true ones moved rigidly: the fix is the fingertip
// moved with them (triangulation in the believed head, as the robot would perceive it).
TEST(MarkerTracker, TriangulatesThroughTheBelievedHeadKinematics) {
  Harness h(graph("joint_offsets_deg: 'neck_yaw: 3, neck_pitch: -2'"));
  const Eigen::VectorXd q = joints(hand_before_eyes());
  const Eigen::Vector3d tip = set_posture(h, q);
  h.step(2);
  Eigen::VectorXd believed = q;
  believed[model().dof_index("neck_yaw")] += somasim::deg_to_rad(3.0);
  believed[model().dof_index("neck_pitch")] -= somasim::deg_to_rad(2.0);
  const auto cam_true = somasim::render::camera_for(model(), "left_eye", link_poses(q));
  const auto cam_believed = somasim::render::camera_for(model(), "left_eye", link_poses(believed));
  const Eigen::Vector3d expected = cam_believed.pose_root * (cam_true.pose_root.inverse() * tip);
  const auto& s = h.output<Stimulus>("track.stimulus");
  ASSERT_TRUE(s.present);
  EXPECT_GT((expected - tip).norm(), 0.01);  // the offset matters
  EXPECT_LT((s.position - expected).norm(), 0.002);
}

// The robot's belief of where its fingertip is (encoders + joint_offsets_deg) gates the fixes:
// arm offsets of generated sizes move the believed marker away from the seen one; a fix is
// kept while it lies within max_distance_from_believed of the belief and refused beyond it.
TEST(MarkerTracker, FixesFarFromTheBelievedFingertipAreRefused) {
  const Eigen::VectorXd q = joints(hand_before_eyes());
  for (const double shoulder_deg : {-16.0, -8.0, -2.0, 2.0, 8.0, 16.0}) {
    for (const double gate : {0.0, 0.06}) {
      SCOPED_TRACE(::testing::Message() << "offset " << shoulder_deg << " deg, gate " << gate);
      Harness h(graph("joint_offsets_deg: 'r_shoulder_pitch: " + std::to_string(shoulder_deg) +
                      "', max_distance_from_believed: " + std::to_string(gate)));
      const Eigen::Vector3d tip = set_posture(h, q);
      Eigen::VectorXd believed_q = q;
      believed_q[model().dof_index("r_shoulder_pitch")] += somasim::deg_to_rad(shoulder_deg);
      const auto tip_ref = model().frame_ref("r_index_tip");
      const Eigen::Vector3d believed =
          link_poses(believed_q)[static_cast<std::size_t>(tip_ref.link)] *
          tip_ref.pose.translation();
      const double off = (believed - tip).norm();
      h.step(2);
      const auto& s = h.output<Stimulus>("track.stimulus");
      const bool kept = gate == 0.0 || off <= gate - 0.002;
      const bool refused = gate > 0.0 && off > gate + 0.002;
      if (kept) {
        ASSERT_TRUE(s.present) << off;
        EXPECT_LT((s.position - tip).norm(), 0.002);
      }
      if (refused) {
        EXPECT_FALSE(s.present) << off;
      }
      h.finish();
      if (gate > 0.0) {
        EXPECT_EQ(h.metric("track", "far_from_believed_rejections"), refused ? 2 : 0) << off;
      } else {
        EXPECT_TRUE(h.metric("track", "far_from_believed_rejections").is_null());
      }
    }
  }
}

// A cluttered background (rectangles of random colours from the seed) around the hand.
TEST(MarkerTracker, TexturedBackground) {
  for (int seed : {1, 2, 3}) {
    Harness h(graph("", ", background: textured", seed));
    const Eigen::Vector3d tip = set_posture(h, joints(hand_before_eyes()));
    h.step(2);
    const auto& s = h.output<Stimulus>("track.stimulus");
    EXPECT_TRUE(s.present) << "seed " << seed;
    EXPECT_LT((s.position - tip).norm(), 0.002) << "seed " << seed;
  }
}

TEST(MarkerTracker, SameSeedGivesIdenticalOutputs) {
  auto run = [] {
    Harness h(graph("", ", background: textured"));
    auto p = hand_before_eyes();
    std::vector<double> out;
    for (int k = 0; k < 5; ++k) {
      p["r_elbow"] = 40 + k;
      set_posture(h, joints(p));
      h.step(1);
      const auto& s = h.output<Stimulus>("track.stimulus");
      for (int i = 0; i < 3; ++i) out.insert(out.end(), {s.position[i], s.velocity[i]});
    }
    return out;
  };
  EXPECT_EQ(run(), run());
}

TEST(MarkerTracker, ColourRangeThatMatchesNothingIsARunErrorWhenTheMarkerIsInView) {
  Harness h(graph("hsv_low: [140, 80, 40], hsv_high: [160, 255, 255], no_colour_frames_error: 3"));
  set_posture(h, joints(hand_before_eyes()));
  h.step(2);  // two frames: could be a hidden marker
  EXPECT_FALSE(h.output<Stimulus>("track.stimulus").present);
  try {
    h.step(1);
    FAIL() << "no error";
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "no pixel of camera 'left_eye' or 'right_eye' has been in the colour range "
                 "hsv_low [140, 80, 40] .. hsv_high [160, 255, 255] for 3 frames (since t = "
                 "0.000 s), while the believed kinematics put the marker ('r_index_tip') in view "
                 "of both: is the range the marker's colour (OpenCV HSV: H 0-179, S and V "
                 "0-255)?");
  }
}

TEST(MarkerTracker, ColourRangeThatMatchesNothingIsNoErrorWhileTheMarkerIsOutOfView) {
  Harness h(graph("hsv_low: [140, 80, 40], hsv_high: [160, 255, 255], no_colour_frames_error: 3"));
  set_posture(h, joints({}));  // arm down: the fingertip is out of view
  h.step(5);
  EXPECT_FALSE(h.output<Stimulus>("track.stimulus").present);
  h.finish();
  EXPECT_EQ(h.metric("track", "frames_in_view"), 0);
  EXPECT_EQ(h.metric("track", "tracked_share"), 0.0);
}

TEST(MarkerTracker, CameraNotInTheRobotModelIsAClearError) {
  EXPECT_EQ(input_error(graph("cameras: [left_eye, nose]")),
            "<inline>:11:23: node 'track', key 'params.cameras': camera 'nose' is not in robot "
            "'icub_v1' (cameras: left_eye, right_eye)");
}

TEST(MarkerTracker, BadColourRangeIsAClearError) {
  EXPECT_EQ(input_error(graph("hsv_low: [190, 80, 40]")),
            "<inline>:11:23: node 'track', key 'params.hsv_low': hue 190 is above 179 (OpenCV's "
            "hue is degrees / 2)");
  EXPECT_EQ(input_error(graph("hsv_low: [45, 200, 40], hsv_high: [75, 100, 255]")),
            "<inline>:11:23: node 'track', key 'params.hsv_low': saturation 200 is above "
            "hsv_high's 100");
}

TEST(MarkerTracker, ImagesOfAnotherSizeThanTheCalibrationAreARunError) {
  Harness h("seed: 1\nbase_rate_hz: 30\nrobots: {icub: " + kRobot +
            "}\nnodes:\n  track:\n    plugin: marker_tracker\n"
            "    inputs: {left_eye_rgb: harness.left, right_eye_rgb: harness.right, "
            "joint_state: harness.q}\n");
  h.input<JointState>("q").position = Eigen::VectorXd::Zero(model().num_dofs());
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
