// bullet_world: guided objects (dynamic bodies pulled along a constant-velocity path by a
// bounded force) follow their path in free space, are stopped by the robot instead of driving
// it, and never blow the world up, whatever link they are aimed at; blow-ups that still happen
// name the bodies in contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::ObjectMotion;
using somasim::ObjectShape;
using somasim::ObjectSpawn;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::RunError;
using somasim::testing::Harness;
using namespace world_test;

namespace {

// The sum of the normal forces [N] on object 0 over the points of a step.
double force_on_object(const Contacts& contacts) {
  double f = 0.0;
  for (const auto& c : contacts.points)
    if (c.object_b == 0 || c.object_a == 0) f += c.normal_force;
  return f;
}

ObjectSpawn guided_sphere(const Eigen::Vector3d& start, const Eigen::Vector3d& velocity,
                          double radius = 0.02) {
  auto s = sphere(1, "held", radius, start, ObjectMotion::kGuided);
  s.linear_velocity = velocity;
  return s;
}

}  // namespace

TEST(GuidedObjects, FollowTheirPathInFreeSpaceWithoutGravity) {
  Harness h(world_yaml("locked_joints: all"));
  const Eigen::Vector3d start(-0.8, 0.4, 0.3), v(0.05, -0.12, 0.03);
  h.input<ObjectSpawns>("spawns").recent = {guided_sphere(start, v)};
  h.step(500);
  const auto& objects = h.output<ObjectStates>("world.objects");
  ASSERT_TRUE(objects.present[0]);
  EXPECT_LT((objects.poses[0].translation() - (start + 0.5 * v)).norm(), 1e-9);
  EXPECT_LT((objects.linear_velocity[0] - v).norm(), 1e-9);
  EXPECT_TRUE(objects.poses[0].linear().isIdentity(1e-12));  // held: no rotation
}

TEST(GuidedObjects, AreStoppedByALockedArmPressingWithAtMostTheirForce) {
  const auto model = icub();
  const Eigen::VectorXd q = with_joints_deg(*model, rest_posture(*model),
                                            {{"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}});
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const Eigen::Isometry3d& forearm = data.link_poses[model->link_index("l_forearm")];
  const Eigen::Vector3d normal = forearm.linear() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d skin = forearm * Eigen::Vector3d(0, -0.07, 0) + 0.020 * normal;
  // Rigid, and soft as the skin (3 N sink 3 mm at 1000 N/m).
  for (const double stiffness : {0.0, 1000.0}) {
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q) +
                         ", locked_joints: all, guide_max_force: 3, guide_contact_stiffness: " +
                         std::to_string(stiffness)));
    // 10 mm from the skin at 0.1 m/s: its path runs 90 mm into the forearm within the second.
    h.input<ObjectSpawns>("spawns").recent = {
        guided_sphere(skin + 0.03 * normal, -0.1 * normal, 0.02)};
    const auto& contacts = h.output<Contacts>("world.contacts");
    // The impact (0.1 kg stopped from 0.1 m/s) is over within a few steps; then it presses.
    double max_force = 0.0, pressing = 0.0;
    for (int k = 0; k < 1000; ++k) {
      h.step();
      if (k >= 500) max_force = std::max(max_force, force_on_object(contacts));
      if (k == 999) pressing = force_on_object(contacts);
    }
    const auto& objects = h.output<ObjectStates>("world.objects");
    const double depth = 0.02 - (objects.poses[0].translation() - skin).dot(normal);
    const double expected = stiffness > 0 ? 3.0 / stiffness : 0.0;
    EXPECT_NEAR(depth, expected, 0.001) << "stiffness " << stiffness;
    EXPECT_NEAR(pressing, 3.0, 0.05) << "the guide's bound, saturated";
    EXPECT_LT(max_force, 3.0 + 0.05);
    h.finish();
    EXPECT_LT(h.metric("world", "max_penetration_m").get<double>(), expected + 0.001);
  }
}

TEST(GuidedObjects, AFreeRobotHitAnywhereNeverBlowsUp) {
  // Generated cases: shapes of radius 1.5-6 cm at 0.02-0.30 m/s aimed at random links of the
  // free robot (every joint motorised and holding its posture), their paths running 10 cm
  // through the link; a kinematic object on the same paths may wedge a link and drive a joint
  // without bound, a guided one may not.
  const auto model = icub();
  const Eigen::VectorXd q = rest_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int cases = 0, kinematic_failures = 0;
  for (int trial = 0; cases < 24 && trial < 200; ++trial) {
    const int link = static_cast<int>(unit(rng) * model->num_links()) % model->num_links();
    if (model->link(link).collision.empty()) continue;
    const auto& geom = model->link(link).collision.front();
    const Eigen::Vector3d target = data.link_poses[link] * geom.origin.translation();
    Eigen::Vector3d dir(gauss(rng), gauss(rng), gauss(rng));
    dir.normalize();
    const double size = 0.015 + 0.045 * unit(rng);
    const double speed = 0.02 + 0.28 * unit(rng);
    const Eigen::Vector3d start = target + (0.25 + size) * dir;
    ObjectSpawn s;
    s.id = 1;
    s.name = "probe";
    s.motion = ObjectMotion::kGuided;
    const int shape = trial % 3;
    s.shape = shape == 0 ? ObjectShape::kSphere
                         : (shape == 1 ? ObjectShape::kBox : ObjectShape::kCylinder);
    s.size = shape == 0 ? Eigen::Vector3d(size, 0, 0)
                        : (shape == 1 ? Eigen::Vector3d::Constant(size / std::sqrt(3.0))
                                      : Eigen::Vector3d(size, 0.06, 0));
    s.pose.translation() = start;
    s.linear_velocity = -speed * dir;
    s.remove_after_s = (0.25 + size + 0.10) / speed;
    const auto run = [&](ObjectMotion motion) {
      Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q)));
      h.input<somasim::JointCommand>("cmd") = hold(q);
      s.motion = motion;
      h.input<ObjectSpawns>("spawns").recent = {s};
      try {
        h.step(static_cast<int>(std::ceil(s.remove_after_s * 1000.0)) + 50);
      } catch (const RunError& e) {
        return std::string(e.what());
      }
      return std::string();
    };
    const std::string failure = run(ObjectMotion::kGuided);
    if (failure.find("starts inside the robot") != std::string::npos) continue;  // not placed
    ++cases;
    EXPECT_EQ(failure, "") << fmt::format("link '{}', size {:.3f} m, speed {:.2f} m/s",
                                          model->link(link).name, size, speed);
    if (!run(ObjectMotion::kKinematic).empty()) ++kinematic_failures;
  }
  EXPECT_EQ(cases, 24);
  // The class this closes (not asserted: how often a kinematic path wedges depends on the cases).
  RecordProperty("kinematic_blowups", kinematic_failures);
  std::printf("same paths, kinematic objects: %d of %d runs stopped\n", kinematic_failures, cases);
}

TEST(GuidedObjects, ABlowUpNamesTheBodiesInContact) {
  // A kinematic box drives the free head's yaw: the joint speed bound is set low enough that the
  // push alone trips it, and the message names who was touching whom.
  const auto model = icub();
  const Eigen::VectorXd q = rest_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const int head = model->link_index("head");
  const auto& geom = model->link(head).collision.front();
  const Eigen::Vector3d centre = data.link_poses[head] * geom.origin.translation();
  auto s =
      sphere(1, "fist", 0.03, centre + Eigen::Vector3d(-0.02, 0.15, 0.0), ObjectMotion::kKinematic);
  s.linear_velocity = Eigen::Vector3d(0, -0.5, 0);
  Harness h(
      world_yaml("initial_posture_deg: " + posture_param(*model, q) + ", max_joint_speed: 0.5"));
  h.input<somasim::JointCommand>("cmd") = hold(q);
  h.input<ObjectSpawns>("spawns").recent = {s};
  std::string msg;
  try {
    h.step(1000);
  } catch (const RunError& e) {
    msg = e.what();
  }
  EXPECT_EQ(msg.rfind("physics blow-up at t = ", 0), 0u) << msg;
  EXPECT_NE(msg.find("bodies in contact: link '"), std::string::npos) << msg;
  EXPECT_NE(msg.find("object 'fist' ("), std::string::npos) << msg;
}
