// bullet_world with `joint_motion: kinematic`: the joints follow their commands exactly (at most
// max_joint_speed), link poses are the forward kinematics of the joint state, a dynamic ball
// meeting a moving arm is pushed with a reported contact force, static objects and other links
// touched by a kinematic link are reported (unsolved, stiffness × depth), and locked joints
// still refuse commands.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::JointState;
using somasim::LinkPoses;
using somasim::ObjectMotion;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::testing::Harness;
using namespace world_test;

namespace {

constexpr double kDeg = M_PI / 180.0;

// A smooth command of the left arm: shoulder pitch and elbow on sinusoids around `q0`.
JointCommand waving(const somasim::robot::RobotModel& model, const Eigen::VectorXd& q0, double t) {
  JointCommand c = hold(q0);
  const int pitch = model.dof_index("l_shoulder_pitch"), elbow = model.dof_index("l_elbow");
  c.position[pitch] = q0[pitch] + 20 * kDeg * std::sin(2.0 * t);
  c.velocity[pitch] = 40 * kDeg * std::cos(2.0 * t);
  c.position[elbow] = q0[elbow] + 15 * kDeg * std::sin(3.0 * t);
  c.velocity[elbow] = 45 * kDeg * std::cos(3.0 * t);
  return c;
}

}  // namespace

TEST(KinematicRobot, JointsFollowTheirCommandsExactly) {
  const auto model = icub();
  const Eigen::VectorXd q0 =
      with_joints_deg(*model, rest_posture(*model), {{"l_shoulder_pitch", -40}, {"l_elbow", 60}});
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", joint_motion: kinematic, locked_joints: [torso_pitch]"));
  auto& cmd = h.input<JointCommand>("cmd");
  const auto& state = h.output<JointState>("world.joint_state");
  const auto& poses = h.output<LinkPoses>("world.link_poses");
  somasim::robot::RobotData fk(*model);
  double worst = 0.0;
  const int locked = model->dof_index("torso_pitch");
  for (int k = 0; k < 2000; ++k) {
    const double t = k * 1e-3;
    cmd = waving(*model, q0, t);
    cmd.mode[static_cast<std::size_t>(locked)] = JointCommandMode::kNone;
    h.step();
    worst = std::max(worst, (state.position - cmd.position).cwiseAbs().maxCoeff());
    if (k % 100 == 0) {
      somasim::robot::forward_kinematics(*model, fk, state.position);
      for (int i = 0; i < model->num_links(); ++i)
        ASSERT_LT((poses.poses[i].matrix() - fk.link_poses[i].matrix()).norm(), 1e-9) << k;
    }
  }
  EXPECT_LT(worst, 1e-12);  // exact: the state is the command
  // Velocity: the step's own motion, close to the command's feed-forward.
  const int elbow = model->dof_index("l_elbow");
  EXPECT_NEAR(state.velocity[elbow], cmd.velocity[elbow], 0.002);
}

TEST(KinematicRobot, AStepCommandMovesAtMostMaxJointSpeed) {
  const auto model = icub();
  const Eigen::VectorXd q0 = rest_posture(*model);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", joint_motion: kinematic, max_joint_speed: 2"));
  auto& cmd = h.input<JointCommand>("cmd");
  cmd = hold(q0);
  const int elbow = model->dof_index("l_elbow");
  cmd.position[elbow] = q0[elbow] + 0.5;  // a 0.5 rad step
  const auto& state = h.output<JointState>("world.joint_state");
  h.step(100);  // 0.1 s at < 2 rad/s: 0.2 rad
  EXPECT_NEAR(state.position[elbow] - q0[elbow], 0.1 * 2 * 0.999, 1e-9);
  h.step(200);
  EXPECT_NEAR(state.position[elbow], q0[elbow] + 0.5, 1e-12);
  EXPECT_EQ(h.finish(), "");
}

TEST(KinematicRobot, AMovingArmPushesABallWithAReportedForce) {
  const auto model = icub();
  const Eigen::VectorXd q0 =
      with_joints_deg(*model, rest_posture(*model),
                      {{"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}, {"l_elbow", 60}});
  const int forearm = model->link_index("l_forearm");
  const int pitch = model->dof_index("l_shoulder_pitch");
  // Where a point of the forearm's skin goes when the shoulder pitch decreases: the ball waits
  // 5 mm ahead of it (no gravity), in the way of the arm.
  somasim::robot::RobotData fk(*model);
  somasim::robot::forward_kinematics(*model, fk, q0);
  const Eigen::Isometry3d pose = fk.link_poses[forearm];
  Eigen::VectorXd q1 = q0;
  q1[pitch] -= 0.01;
  somasim::robot::forward_kinematics(*model, fk, q1);
  const Eigen::Vector3d axis = pose.linear() * Eigen::Vector3d::UnitY();  // the forearm's
  const Eigen::Vector3d on_axis = pose * Eigen::Vector3d(0, -0.07, 0);
  Eigen::Vector3d ahead = fk.link_poses[forearm] * Eigen::Vector3d(0, -0.07, 0) - on_axis;
  ahead = (ahead - ahead.dot(axis) * axis).normalized();
  const Eigen::Vector3d centre = on_axis + (0.021 + 0.005 + 0.02) * ahead;
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", joint_motion: kinematic, gravity: [0, 0, 0]"));
  h.input<ObjectSpawns>("spawns").recent = {sphere(1, "ball", 0.02, centre)};
  auto& cmd = h.input<JointCommand>("cmd");
  const auto& contacts = h.output<Contacts>("world.contacts");
  const auto& objects = h.output<ObjectStates>("world.objects");
  double max_force = 0.0;
  int points = 0;
  for (int k = 0; k < 300; ++k) {
    cmd = hold(q0);
    cmd.position[pitch] = q0[pitch] - 0.5 * k * 1e-3;  // 0.5 rad/s into the ball
    h.step();
    for (const auto& c : contacts.points)
      if (c.link_a >= 0 && c.object_b == 0)
        max_force = std::max(max_force, c.normal_force), ++points;
  }
  EXPECT_GT(points, 0);
  EXPECT_GT(max_force, 0.0);
  EXPECT_GT((objects.poses[0].translation() - centre).norm(), 0.005);  // the ball was pushed
  EXPECT_EQ(h.finish(), "");
}

TEST(KinematicRobot, LockedJointsStillRefuseCommands) {
  const auto model = icub();
  const Eigen::VectorXd q0 = rest_posture(*model);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", joint_motion: kinematic, locked_joints: [l_elbow]"));
  auto& cmd = h.input<JointCommand>("cmd");
  cmd = hold(q0);
  EXPECT_THROW(h.step(), somasim::RunError);
}
