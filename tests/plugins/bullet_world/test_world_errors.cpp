// bullet_world: bad input and trouble during a run, whole messages asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "world_test_support.hpp"

using somasim::InputError;
using somasim::JointCommand;
using somasim::ObjectSpawns;
using somasim::RunError;
using somasim::testing::Harness;
using namespace world_test;

namespace {

template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<no exception>";
}

}  // namespace

TEST(BulletWorldErrors, AMeshThatCannotBeUsedIsNamedWithItsNodeKeyAndObject) {
  const TempFile mesh("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  const TempFile scene("scene.yaml", "objects:\n  - name: cup\n    shape: mesh\n    file: " +
                                         mesh.str() + "\n    xyz: [0.3, 0, 0.5]\n");
  const std::string msg =
      message_of<InputError>([&] { Harness h(world_yaml("scene: " + scene.str())); });
  EXPECT_EQ(msg, "<inline>:6:21: node 'world', key 'params.scene': " + scene.str() +
                     ":2:5: object 'cup': mesh file '" + mesh.str() +
                     "': vertex 2 of mesh 0 is not finite (0.000000, nan, 0.000000)");
}

TEST(BulletWorldErrors, ARobotMeshThatCannotBeUsedIsNamedWithItsRobotEntry) {
  const TempFile mesh("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
  const TempFile robot("robot.yaml",
                       "robot: r\nlinks:\n  root:\n    mass: 1\n"
                       "    collision: [{type: mesh, file: " +
                           mesh.str() + "}]\n");
  const std::string msg = message_of<InputError>([&] {
    Harness h("base_rate_hz: 1000\nrobots: {r: " + robot.str() +
              "}\nnodes:\n  world: {plugin: bullet_world}\n");
  });
  EXPECT_EQ(msg, "<inline>:2:13: robot 'r' (used by node 'world'): mesh file '" + mesh.str() +
                     "': vertex 2 of mesh 0 is not finite (0.000000, inf, 0.000000)");
}

TEST(BulletWorldErrors, UnknownObjectTypeInTheScene) {
  const TempFile scene("scene.yaml",
                       "objects:\n"
                       "  - {name: ball, shape: sphere, radius: 0.02, xyz: [-0.6, 0, 0.5]}\n"
                       "  - {name: dice, shape: cube, size: [0.02, 0.02, 0.02]}\n");
  const std::string msg =
      message_of<InputError>([&] { Harness h(world_yaml("scene: " + scene.str())); });
  EXPECT_EQ(msg, "<inline>:6:" + std::to_string(21) +
                     ": node 'world', key 'params.scene': " + scene.str() +
                     ":3:25: key 'objects[1].shape': unknown object type 'cube'; expected one of "
                     "box, cylinder, mesh, sphere");
}

TEST(BulletWorldErrors, ObjectStartingInsideTheRobot) {
  const TempFile scene("scene.yaml",
                       "objects:\n"
                       "  - {name: intruder, shape: sphere, radius: 0.03, motion: static,"
                       " xyz: [0, 0, 0.15]}\n");
  const std::string msg =
      message_of<InputError>([&] { Harness h(world_yaml("scene: " + scene.str())); });
  EXPECT_EQ(msg, scene.str() +
                     ":2:5: object 'intruder' starts inside the robot: it overlaps "
                     "link 'chest' by 70.0 mm");
}

TEST(BulletWorldErrors, ObjectSpawnedInsideTheRobot) {
  const auto model = icub();
  Harness h(world_yaml());
  h.step(10);
  h.input<ObjectSpawns>("spawns").recent = {
      sphere(4, "ghost", 0.03, Eigen::Vector3d(-0.0, 0.0, 0.15))};
  const std::string msg = message_of<RunError>([&] { h.step(); });
  EXPECT_EQ(msg,
            "t = 0.010 s: spawned object 'ghost' (id 4) starts inside the robot: it "
            "overlaps link 'chest' by 70.0 mm");
}

TEST(BulletWorldErrors, NaNInACommandPort) {
  const auto model = icub();
  {
    Harness h(world_yaml());
    JointCommand cmd = hold(rest_posture(*model));
    cmd.position[model->dof_index("r_elbow")] = std::numeric_limits<double>::quiet_NaN();
    h.step(5);
    h.input<JointCommand>("cmd") = cmd;
    EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
              "t = 0.005 s: joint command for 'r_elbow': the position target is nan");
  }
  {
    Harness h(world_yaml());
    JointCommand cmd = hold(rest_posture(*model));
    cmd.mode[model->dof_index("l_wrist_yaw")] = somasim::JointCommandMode::kVelocity;
    cmd.velocity[model->dof_index("l_wrist_yaw")] = std::numeric_limits<double>::infinity();
    h.input<JointCommand>("cmd") = cmd;
    EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
              "t = 0.000 s: joint command for 'l_wrist_yaw': the velocity target is inf");
  }
  {
    Harness h(world_yaml());
    JointCommand cmd = hold(rest_posture(*model));
    cmd.mode.resize(7);
    h.input<JointCommand>("cmd") = cmd;
    EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
              "t = 0.000 s: joint command: expected 23 modes, got 7");
  }
}

TEST(BulletWorldErrors, UnknownJointInTheInitialPosture) {
  EXPECT_EQ(
      message_of<InputError>([&] { Harness h(world_yaml("initial_posture_deg: 'r_elbw: 30'")); }),
      "<inline>:6:" + std::to_string(35) +
          ": node 'world', key 'params.initial_posture_deg': unknown joint 'r_elbw' (did "
          "you mean 'r_elbow'?) (movable joints of the robot)");
  EXPECT_EQ(
      message_of<InputError>([&] { Harness h(world_yaml("initial_posture_deg: 'r_elbow: 200'")); }),
      "<inline>:6:" + std::to_string(35) +
          ": node 'world', key 'params.initial_posture_deg': joint 'r_elbow': 200 deg is "
          "outside the limits [5.5, 106]");
}

TEST(BulletWorldErrors, PhysicsBlowUpStopsTheRunNamingTimeAndBody) {
  Harness h(world_yaml());
  auto s = sphere(1, "bullet", 0.01, Eigen::Vector3d(-1, 0, 0.5));
  s.linear_velocity = Eigen::Vector3d(0, 0, 80);
  h.input<ObjectSpawns>("spawns").recent = {s};
  EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
            "physics blow-up at t = 0.001 s: object 'bullet' moves at 80.0 m/s "
            "(max_object_speed: 50 m/s); no bodies in contact");
}

// A gravity 10^6 times Earth's: the joints run into Bullet's speed clamp within a few
// steps; the blow-up check (below that clamp) must see it, not let the run "complete".
TEST(BulletWorldErrors, HugeGravityIsCaughtAsABlowUp) {
  Harness h(world_yaml("gravity: [0, 0, -1e7]"));
  const std::string msg = message_of<RunError>([&] { h.step(100); });
  EXPECT_EQ(msg.rfind("physics blow-up at t = ", 0), 0u) << msg;
  EXPECT_NE(msg.find("rad/s (max_joint_speed: 99 rad/s)"), std::string::npos) << msg;
}

TEST(BulletWorldErrors, AGuideTooStiffForTheStepIsALocatedError) {
  const std::string msg =
      message_of<InputError>([&] { Harness h(world_yaml("guide_bandwidth: 800")); });
  EXPECT_NE(msg.find("node 'world', key 'params.guide_bandwidth': 800 1/s at a 0.001 s step makes "
                     "the guide unstable: keep guide_bandwidth x step <= 0.5 (here <= 500 1/s)"),
            std::string::npos)
      << msg;
}

TEST(BulletWorldErrors, BadSpawnRequest) {
  Harness h(world_yaml());
  auto s = sphere(3, "flat", 0.0, Eigen::Vector3d(-1, 0, 0.5));
  h.input<ObjectSpawns>("spawns").recent = {s};
  EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
            "t = 0.000 s: spawned object 'flat' (id 3): sphere radius must be > 0 m, got 0");
}

TEST(BulletWorldErrors, CommandOnALockedJoint) {
  const auto model = icub();
  Harness h(world_yaml("locked_joints: 'l_elbow r_elbow'"));
  JointCommand cmd = hold(rest_posture(*model));
  h.step(3);
  h.input<JointCommand>("cmd") = cmd;
  EXPECT_EQ(message_of<RunError>([&] { h.step(); }),
            "t = 0.003 s: joint command for 'r_elbow': the joint is locked (param "
            "locked_joints); send kNone for it");
  // kNone on the locked joints is fine.
  Harness h2(world_yaml("locked_joints: 'l_elbow r_elbow'"));
  cmd.mode[model->dof_index("l_elbow")] = somasim::JointCommandMode::kNone;
  cmd.mode[model->dof_index("r_elbow")] = somasim::JointCommandMode::kNone;
  h2.input<JointCommand>("cmd") = cmd;
  EXPECT_NO_THROW(h2.step(10));
}

TEST(BulletWorldErrors, UnknownOrFixedLockedJoint) {
  const std::string where =
      "<inline>:6:" + std::to_string(29) + ": node 'world', key 'params.locked_joints': ";
  EXPECT_EQ(message_of<InputError>([&] { Harness h(world_yaml("locked_joints: 'l_elbw'")); }),
            where + "robot 'icub_v1': unknown joint 'l_elbw' (did you mean 'l_elbow'?)");
  EXPECT_EQ(message_of<InputError>(
                [&] { Harness h(world_yaml("locked_joints: 'all, left_arm_2_fixed'")); }),
            where +
                "robot 'icub_v1': joint 'left_arm_2_fixed' is fixed; expected a revolute or "
                "prismatic joint");
}
