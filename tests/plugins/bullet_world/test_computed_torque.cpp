// bullet_world with `joint_servo: computed_torque`: joint torques from the robot's inverse
// dynamics hold postures under gravity and track moving commands (positions with feed-forward,
// velocities) within a fraction of a degree, at any posture drawn at random and with some joints
// locked; objects that hit the arm push it and it comes back; a gain the step cannot integrate is
// refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::JointState;
using somasim::ObjectSpawns;
using somasim::testing::Harness;
using namespace world_test;

namespace {

constexpr double kDeg = M_PI / 180.0;

}  // namespace

TEST(ComputedTorque, HoldsRandomPosturesUnderGravity) {
  const auto model = icub();
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q0 = random_posture(*model, rng);
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                         ", joint_servo: computed_torque"));
    h.input<JointCommand>("cmd") = hold(q0);
    const auto& state = h.output<JointState>("world.joint_state");
    h.step(1000);
    EXPECT_LT((state.position - q0).cwiseAbs().maxCoeff(), 0.05 * kDeg) << trial;
    EXPECT_EQ(h.finish(), "");
  }
}

TEST(ComputedTorque, TracksMovingPositionAndVelocityCommands) {
  const auto model = icub();
  std::mt19937 rng(8);
  for (const std::string locked : {"[]", "[torso_pitch, torso_roll, torso_yaw, neck_pitch]"}) {
    const Eigen::VectorXd q0 = random_posture(*model, rng);
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                         ", joint_servo: computed_torque, locked_joints: " + locked));
    auto& cmd = h.input<JointCommand>("cmd");
    const auto& state = h.output<JointState>("world.joint_state");
    const int pitch = model->dof_index("l_shoulder_pitch"), elbow = model->dof_index("l_elbow");
    const int wrist = model->dof_index("r_wrist_pitch");
    double worst = 0.0, worst_velocity = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const double t = k * 1e-3;
      cmd = hold(q0);
      if (locked != "[]")
        for (const char* name : {"torso_pitch", "torso_roll", "torso_yaw", "neck_pitch"})
          cmd.mode[static_cast<std::size_t>(model->dof_index(name))] = JointCommandMode::kNone;
      cmd.position[pitch] = q0[pitch] + 10 * kDeg * std::sin(2.0 * t);
      cmd.velocity[pitch] = 20 * kDeg * std::cos(2.0 * t);
      cmd.position[elbow] = q0[elbow] + 10 * kDeg * std::sin(3.0 * t);
      cmd.velocity[elbow] = 30 * kDeg * std::cos(3.0 * t);
      cmd.mode[static_cast<std::size_t>(wrist)] = JointCommandMode::kVelocity;
      cmd.velocity[wrist] = 10 * kDeg * std::cos(4.0 * t);
      h.step();
      if (t < 0.5) continue;
      for (const int d : {pitch, elbow})
        worst = std::max(worst, std::abs(state.position[d] - cmd.position[d]));
      worst_velocity =
          std::max(worst_velocity, std::abs(state.velocity[wrist] - cmd.velocity[wrist]));
    }
    SCOPED_TRACE(locked);
    EXPECT_LT(worst, 0.2 * kDeg);
    EXPECT_LT(worst_velocity, 1.0 * kDeg);
    EXPECT_EQ(h.finish(), "");
  }
}

TEST(ComputedTorque, ABallHittingTheForearmPushesItAndItComesBack) {
  const auto model = icub();
  const Eigen::VectorXd q0 =
      with_joints_deg(*model, rest_posture(*model),
                      {{"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}, {"l_elbow", 60}});
  somasim::robot::RobotData fk(*model);
  somasim::robot::forward_kinematics(*model, fk, q0);
  const Eigen::Vector3d target =
      fk.link_poses[model->link_index("l_forearm")] * Eigen::Vector3d(0, -0.07, 0);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", joint_servo: computed_torque"));
  somasim::ObjectSpawn ball = sphere(1, "ball", 0.02, target + Eigen::Vector3d(0, 0, 0.2));
  ball.mass = 0.2;
  ball.linear_velocity = Eigen::Vector3d(0, 0, -2.0);
  h.input<ObjectSpawns>("spawns").recent = {ball};
  h.input<JointCommand>("cmd") = hold(q0);
  const auto& state = h.output<JointState>("world.joint_state");
  const auto& contacts = h.output<Contacts>("world.contacts");
  double pushed = 0.0;
  int touching = 0;
  for (int k = 0; k < 300; ++k) {
    h.step();
    pushed = std::max(pushed, (state.position - q0).cwiseAbs().maxCoeff());
    for (const auto& c : contacts.points) touching += c.link_a >= 0 && c.object_b == 0;
  }
  EXPECT_GT(touching, 0);
  EXPECT_GT(pushed, 0.01 * kDeg);  // the arm yields to the hit (no rigid motor)
  h.input<ObjectSpawns>("spawns").withdraw = {"ball"};
  h.step(700);
  EXPECT_LT((state.position - q0).cwiseAbs().maxCoeff(), 0.05 * kDeg);
  EXPECT_EQ(h.finish(), "");
}

TEST(ComputedTorque, AGainTheStepCannotIntegrateIsRefused) {
  try {
    Harness h(world_yaml("joint_servo: computed_torque, position_gain: 400"));
    FAIL() << "accepted";
  } catch (const somasim::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("position_gain"), std::string::npos) << what;
    EXPECT_NE(what.find("<= 250"), std::string::npos) << what;
  }
}
