// The `gaze_controller` plugin through the public harness, with an ideal position-controlled
// head (the command fed back as the encoders): the target ends in the middle of both images at
// a bounded joint speed; out-of-reach targets are clamped and reported; bad joints are located.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"
#include "somasim/units.hpp"

using somasim::JointCommand;
using somasim::JointState;
using somasim::pps::Stimulus;
using somasim::testing::Harness;

namespace {

const std::string kRobot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";

const somasim::robot::RobotModel& model() {
  static const auto m = somasim::robot::load_robot_model_shared(kRobot);
  return *m;
}

std::string graph(const std::string& params = "") {
  return "seed: 1\nbase_rate_hz: 100\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  gaze:\n    plugin: gaze_controller\n    params: {" + params +
         "}\n    inputs: {target: harness.target, joint_state: harness.q}\n";
}

somasim::render::Camera eye(const Eigen::VectorXd& q, const char* name) {
  somasim::robot::RobotData data(model());
  somasim::robot::forward_kinematics(model(), data, q);
  return somasim::render::camera_for(model(), name, data.link_poses);
}

// A point in the left eye's frame at q = 0 [m], in the root frame.
Eigen::Vector3d ahead(const Eigen::Vector3d& in_left_eye) {
  return eye(Eigen::VectorXd::Zero(model().num_dofs()), "left_eye").pose_root * in_left_eye;
}

// Runs `steps` ticks with the command fed back as the encoders; returns the final joints and the
// largest change of a joint between two ticks [rad].
Eigen::VectorXd run(Harness& h, const Eigen::Vector3d& target, int steps, double& max_change) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model().num_dofs());
  auto& stim = h.input<Stimulus>("target");
  stim.present = true;
  stim.position = target;
  max_change = 0.0;
  for (int k = 0; k < steps; ++k) {
    h.input<JointState>("q").position = q;
    h.step(1);
    const JointCommand& c = h.output<JointCommand>("gaze.command");
    for (int d = 0; d < q.size(); ++d)
      if (c.mode[static_cast<std::size_t>(d)] == somasim::JointCommandMode::kPosition) {
        max_change = std::max(max_change, std::abs(c.position[d] - q[d]));
        q[d] = c.position[d];
      }
  }
  return q;
}

}  // namespace

TEST(GazeController, TheTargetEndsInTheMiddleOfBothImages) {
  Harness h(graph("max_speed_deg_s: 60"));
  const Eigen::Vector3d target = ahead({-0.15, 0.1, 0.45});
  double max_change = 0.0;
  const Eigen::VectorXd q = run(h, target, 150, max_change);
  for (const char* name : {"left_eye", "right_eye"}) {
    const auto cam = eye(q, name);
    const Eigen::Vector2d uv = *cam.project(target);
    EXPECT_LT((uv - Eigen::Vector2d(cam.intrinsics.cx, cam.intrinsics.cy)).norm(), 0.5) << name;
  }
  EXPECT_LE(max_change, somasim::deg_to_rad(60.0) / 100 + 1e-12);  // bounded speed
  EXPECT_GT(std::abs(q[model().dof_index("neck_yaw")]), 0.05);     // the neck turned
  h.finish();
  EXPECT_EQ(h.metric("gaze", "out_of_reach_steps"), 0);
}

TEST(GazeController, OutOfReachTargetsAreClampedAndReported) {
  Harness h(graph());
  double max_change = 0.0;
  const Eigen::VectorXd q = run(h, ahead({-2.0, -1.5, 0.3}), 100, max_change);
  int at_limit = 0;
  for (const char* joint : {"neck_pitch", "neck_yaw", "eyes_tilt", "l_eye_pan", "r_eye_pan"}) {
    const int d = model().dof_index(joint);
    EXPECT_GE(q[d], model().lower_limits()[d]) << joint;
    EXPECT_LE(q[d], model().upper_limits()[d]) << joint;
    if (q[d] == model().lower_limits()[d] || q[d] == model().upper_limits()[d]) ++at_limit;
  }
  EXPECT_GE(at_limit, 1);
  h.finish();
  EXPECT_EQ(h.metric("gaze", "out_of_reach_steps"), 100);
  EXPECT_GT(h.metric("gaze", "max_gaze_offset_deg").get<double>(), 10.0);
}

TEST(GazeController, NoTargetHoldsTheHead) {
  Harness h(graph());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model().num_dofs());
  q[model().dof_index("neck_yaw")] = 0.2;
  h.input<JointState>("q").position = q;
  h.step(5);
  EXPECT_DOUBLE_EQ(h.output<JointCommand>("gaze.command").position[model().dof_index("neck_yaw")],
                   0.2);
}

TEST(GazeController, UnknownJointOrCameraIsALocatedError) {
  try {
    Harness h(graph("eye_joints: [eyes_tilt, l_eye_pan, r_eyepan]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:26: node 'gaze', key 'params.eye_joints': gaze: robot 'icub_v1': "
                 "unknown joint 'r_eyepan' (did you mean 'r_eye_pan'?)");
  }
  try {
    Harness h(graph("cameras: [left_eye, nose]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:23: node 'gaze', key 'params.cameras': gaze: camera 'nose' is not in "
                 "robot 'icub_v1' (cameras: left_eye, right_eye)");
  }
  try {
    Harness h(graph("neck_joints: [neck_pitch, nek_yaw]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:27: node 'gaze', key 'params.neck_joints': gaze: robot 'icub_v1': "
                 "unknown joint 'nek_yaw' (did you mean 'neck_yaw'?)");
  }
}
