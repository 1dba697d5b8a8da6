// The `gaze_controller` plugin through the public harness, with an ideal position-controlled
// head (the command fed back as the encoders): the target ends in the middle of both images at
// a bounded joint speed; out-of-reach targets are clamped and reported; bad joints are located.
// Without a target the gaze holds for hold_s, then looks at the believed skin parts (idle
// fixation between them, or scan: each in turn), from the taxels input only.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/skin/ports.hpp"
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

// A graph whose gaze also has the believed taxels wired (idle fixation / scan).
std::string idle_graph(const std::string& params) {
  return "seed: 1\nbase_rate_hz: 100\nrobots: {icub: " + kRobot +
         "}\nnodes:\n  gaze:\n    plugin: gaze_controller\n    params: {" + params +
         "}\n    inputs: {target: harness.target, joint_state: harness.q, taxels: "
         "harness.taxels}\n";
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

// Two skin parts of three taxels each around `a` and `b` [m, root]: centroids a and b.
somasim::SkinTaxels two_parts(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  somasim::SkinTaxels t;
  for (const auto& [name, c] : {std::pair{"part_a", a}, std::pair{"part_b", b}}) {
    somasim::SkinPart p;
    p.name = name;
    p.positions = {c + Eigen::Vector3d(0.01, 0, 0), c - Eigen::Vector3d(0.01, 0, 0), c};
    t.parts.push_back(p);
  }
  return t;
}

// Pixel distance of `p` from the image centre, the larger of the two eyes, at joints `q`.
double off_centre_px(const Eigen::VectorXd& q, const Eigen::Vector3d& p) {
  double worst = 0.0;
  for (const char* name : {"left_eye", "right_eye"}) {
    const auto cam = eye(q, name);
    const auto uv = cam.project(p);
    if (!uv) return 1e9;
    worst = std::max(worst, (*uv - Eigen::Vector2d(cam.intrinsics.cx, cam.intrinsics.cy)).norm());
  }
  return worst;
}

// Runs `steps` ticks from `q` with the command fed back as the encoders (the target input as
// it is); returns the final joints.
Eigen::VectorXd follow(Harness& h, Eigen::VectorXd q, int steps) {
  for (int k = 0; k < steps; ++k) {
    h.input<JointState>("q").position = q;
    h.step(1);
    const JointCommand& c = h.output<JointCommand>("gaze.command");
    for (int d = 0; d < q.size(); ++d)
      if (c.mode[static_cast<std::size_t>(d)] == somasim::JointCommandMode::kPosition)
        q[d] = c.position[d];
  }
  return q;
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

// A joint that moves neither camera (an arm's) or one listed twice: refused, not solved for.
TEST(GazeController, JointsThatDoNotMoveTheEyesOrRepeatAreRefused) {
  try {
    Harness h(graph("neck_joints: [neck_pitch, neck_roll, neck_yaw, l_elbow]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:27: node 'gaze', key 'params.neck_joints': gaze: joint 'l_elbow' "
                 "moves neither camera (left_eye, right_eye): it is not between the robot's root "
                 "and the cameras' links");
  }
  try {
    Harness h(graph("neck_joints: [neck_pitch, neck_roll, neck_yaw, eyes_tilt]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'eyes_tilt' is listed twice"), std::string::npos)
        << e.what();
  }
}

TEST(GazeController, IdleFixationLooksBetweenTheBelievedParts) {
  Harness h(idle_graph("idle: fixation, idle_parts: [part_a, part_b]"));
  const Eigen::Vector3d a = ahead({-0.12, 0.05, 0.40});
  const Eigen::Vector3d b = ahead({0.10, 0.08, 0.35});
  h.input<somasim::SkinTaxels>("taxels") = two_parts(a, b);
  const Eigen::VectorXd q = follow(h, Eigen::VectorXd::Zero(model().num_dofs()), 200);
  EXPECT_LT(off_centre_px(q, 0.5 * (a + b)), 0.5);
  EXPECT_GT(off_centre_px(q, a), 20.0);  // neither part itself is centred
  h.finish();
  EXPECT_EQ(h.metric("gaze", "idle_steps"), 200);
  EXPECT_EQ(h.metric("gaze", "steps_with_target"), 0);
}

TEST(GazeController, FollowsTheTargetHoldsWhenItIsLostThenReturnsHome) {
  Harness h(idle_graph("idle: fixation, idle_parts: [part_a, part_b], hold_s: 0.5"));
  const Eigen::Vector3d a = ahead({-0.12, 0.05, 0.40});
  const Eigen::Vector3d b = ahead({0.10, 0.08, 0.35});
  const Eigen::Vector3d home = 0.5 * (a + b);
  const Eigen::Vector3d target = ahead({0.05, -0.12, 0.45});
  h.input<somasim::SkinTaxels>("taxels") = two_parts(a, b);
  auto& stim = h.input<Stimulus>("target");
  stim.present = true;
  stim.position = target;
  Eigen::VectorXd q = follow(h, Eigen::VectorXd::Zero(model().num_dofs()), 150);
  EXPECT_LT(off_centre_px(q, target), 0.5);  // the gaze followed the tracked object
  EXPECT_GT(off_centre_px(q, home), 20.0);
  stim.present = false;  // the track is lost
  const Eigen::VectorXd held = follow(h, q, 40);
  EXPECT_EQ(held, q);  // within hold_s: the gaze stays where the object was
  q = follow(h, held, 250);
  EXPECT_LT(off_centre_px(q, home), 0.5);  // then home: between the parts
  h.finish();
  EXPECT_EQ(h.metric("gaze", "steps_with_target"), 150);
  EXPECT_EQ(h.metric("gaze", "idle_entries"), 1);
}

TEST(GazeController, IdleScanLooksAtEachPartInTurn) {
  Harness h(idle_graph("idle: scan, idle_parts: [part_a, part_b], hold_s: 0, dwell_s: 1.5"));
  const Eigen::Vector3d a = ahead({-0.12, 0.05, 0.40});
  const Eigen::Vector3d b = ahead({0.10, 0.08, 0.35});
  h.input<somasim::SkinTaxels>("taxels") = two_parts(a, b);
  Eigen::VectorXd q = follow(h, Eigen::VectorXd::Zero(model().num_dofs()), 140);
  EXPECT_LT(off_centre_px(q, a), 0.5);
  q = follow(h, q, 150);  // past 1.5 s: the other part
  EXPECT_LT(off_centre_px(q, b), 0.5);
  q = follow(h, q, 150);  // and back
  EXPECT_LT(off_centre_px(q, a), 0.5);
}

TEST(GazeController, IdleBehaviourNeedsPartsAndTheBelievedTaxels) {
  try {
    Harness h(idle_graph("idle: fixation"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:5:3: node 'gaze', key 'params.idle_parts': idle 'fixation' needs at "
                 "least one skin part");
  }
  try {
    Harness h(graph("idle: scan, idle_parts: [part_a]"));
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "<inline>:7:20: node 'gaze', key 'params.idle': idle 'scan' needs the input "
                 "'taxels' (the believed skin, e.g. believed.taxels) wired");
  }
  Harness h(idle_graph("idle: fixation, idle_parts: [part_a, palm]"));
  h.input<somasim::SkinTaxels>("taxels") = two_parts(ahead({0, 0, 0.4}), ahead({0.1, 0, 0.4}));
  h.input<JointState>("q").position = Eigen::VectorXd::Zero(model().num_dofs());
  try {
    h.step(1);
    FAIL();
  } catch (const somasim::RunError& e) {
    EXPECT_STREQ(e.what(),
                 "gaze_controller: idle_parts: no skin part 'palm' in the input 'taxels' (it has: "
                 "part_a, part_b)");
  }
}
