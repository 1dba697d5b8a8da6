// bullet_world: kinematic objects make contacts with immovable robot geometry (a locked robot,
// the fixed base), where the solver applies no force: the contact carries
// kinematic_contact_stiffness × penetration depth, and the object keeps its path.
#include <gtest/gtest.h>

#include <cmath>

#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::ObjectMotion;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::testing::Harness;
using namespace world_test;

namespace {

constexpr double kRadius = 0.015;  // probe sphere [m]
constexpr double kSpeed = 0.1;     // [m/s]

// Sum of the normal forces [N] and number of the points between `link` and object 0.
std::pair<double, int> force_on(const Contacts& contacts, int link) {
  double force = 0.0;
  int n = 0;
  for (const auto& c : contacts.points)
    if (c.link_a == link && c.object_b == 0) force += c.normal_force, ++n;
  return {force, n};
}

// A kinematic probe starting `gap` [m] (surface to surface) from the skin along `normal`,
// moving against it.
somasim::ObjectSpawn probe(const Eigen::Vector3d& surface_point, const Eigen::Vector3d& normal,
                           double gap) {
  auto s = sphere(1, "probe", kRadius, surface_point + (kRadius + gap) * normal,
                  ObjectMotion::kKinematic);
  s.linear_velocity = -kSpeed * normal;
  return s;
}

struct ForearmScene {
  std::shared_ptr<const somasim::robot::RobotModel> model = icub();
  Eigen::VectorXd q;
  int link = -1;
  Eigen::Vector3d surface_point, normal;  // top of the forearm cylinder (r = 0.02), root frame
  ForearmScene() {
    q = with_joints_deg(*model, rest_posture(*model),
                        {{"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}});
    link = model->link_index("l_forearm");
    somasim::robot::RobotData data(*model);
    somasim::robot::forward_kinematics(*model, data, q);
    const Eigen::Isometry3d& pose = data.link_poses[link];
    normal = pose.linear() * Eigen::Vector3d(0, 0, 1);  // perpendicular to the axis (link y)
    surface_point = pose * Eigen::Vector3d(0, -0.07, 0) + 0.020 * normal;
  }
};

}  // namespace

TEST(KinematicContacts, AKinematicObjectPressesALockedRobotWithStiffnessTimesDepth) {
  ForearmScene scene;
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*scene.model, scene.q) +
                       ", locked_joints: all, kinematic_contact_stiffness: 2000"));
  const double gap = 0.005;
  h.input<ObjectSpawns>("spawns").recent = {probe(scene.surface_point, scene.normal, gap)};
  const auto& contacts = h.output<Contacts>("world.contacts");
  int first_contact = -1;
  for (int k = 1; k <= 300; ++k) {  // 300 ms: 30 mm of travel, 25 mm into the forearm
    h.step();
    const double depth = k * 1e-3 * kSpeed - gap;  // the probe meets the skin after 50 ms
    const auto [force, points] = force_on(contacts, scene.link);
    if (points > 0 && first_contact < 0) first_contact = k;
    if (depth > 0.001) {
      ASSERT_GT(points, 0) << "step " << k;
      EXPECT_NEAR(force, 2000.0 * depth, 2000.0 * 2e-4) << "step " << k;
    }
    for (const auto& c : contacts.points) {
      EXPECT_EQ(c.link_a, scene.link);
      EXPECT_LT(c.normal.dot(scene.normal), -0.99);  // from the probe (b) toward the forearm (a)
    }
  }
  // Reported from 0.5 mm apart (contact_distance), i.e. after 45 ms of the 50 ms to the skin.
  EXPECT_GE(first_contact, 45);
  EXPECT_LE(first_contact, 51);
  // The probe kept its path through the static forearm (deeper than max_penetration 20 mm:
  // a prescribed motion into immovable geometry is not a physics blow-up).
  const auto& objects = h.output<ObjectStates>("world.objects");
  const Eigen::Vector3d start = scene.surface_point + (kRadius + gap) * scene.normal;
  EXPECT_LT((objects.poses[0].translation() - (start - 0.3 * kSpeed * scene.normal)).norm(), 1e-9);
}

TEST(KinematicContacts, TheFixedBaseOfAPartlyLockedRobotFeelsKinematicObjects) {
  // Torso locked: the chest is part of the fixed base (immovable), the arms are free.
  const auto model = icub();
  const Eigen::VectorXd q = rest_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const int chest = model->link_index("chest");
  const auto& box = model->link(chest).collision.at(0);
  const Eigen::Vector3d centre = data.link_poses[chest] * box.origin.translation();
  const Eigen::Vector3d front(-1, 0, 0);  // root x is backward
  const Eigen::Vector3d surface_point = centre + 0.5 * box.size.x() * front;
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q) +
                       ", locked_joints: 'torso_pitch torso_roll torso_yaw'"));
  h.input<ObjectSpawns>("spawns").recent = {probe(surface_point, front, 0.01)};
  const auto& contacts = h.output<Contacts>("world.contacts");
  h.step(200);  // 20 mm of travel: 10 mm into the chest
  const auto [force, points] = force_on(contacts, chest);
  EXPECT_GT(points, 0);
  EXPECT_NEAR(force, 1000.0 * 0.010, 1000.0 * 2e-4);  // the default stiffness, 1000 N/m
}

TEST(KinematicContacts, ZeroStiffnessReportsTheContactWithoutForce) {
  ForearmScene scene;
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*scene.model, scene.q) +
                       ", locked_joints: all, kinematic_contact_stiffness: 0"));
  h.input<ObjectSpawns>("spawns").recent = {probe(scene.surface_point, scene.normal, 0.0)};
  h.step(50);
  const auto [force, points] = force_on(h.output<Contacts>("world.contacts"), scene.link);
  EXPECT_GT(points, 0);
  EXPECT_EQ(force, 0.0);
}

TEST(KinematicContacts, KinematicObjectsStillIgnoreStaticObjects) {
  // A kinematic probe passing through a static box of the world: no contact between objects.
  ForearmScene scene;
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*scene.model, scene.q) +
                       ", locked_joints: all"));
  auto wall = sphere(2, "wall", 0.03, Eigen::Vector3d(-0.5, 0.0, 0.3), ObjectMotion::kStatic);
  auto s = sphere(1, "probe", kRadius, Eigen::Vector3d(-0.5, 0.0, 0.4), ObjectMotion::kKinematic);
  s.linear_velocity = Eigen::Vector3d(0, 0, -kSpeed);
  h.input<ObjectSpawns>("spawns").recent = {wall, s};
  const auto& contacts = h.output<Contacts>("world.contacts");
  for (int k = 0; k < 1000; ++k) {
    h.step();
    ASSERT_TRUE(contacts.points.empty()) << "step " << k;
  }
}
