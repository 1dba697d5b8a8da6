// object_thrower: spawn geometry, perceived stimulus (noise-free and with kinematic offsets),
// parameter errors, determinism. No physics: objects are fed by hand from the spawn requests.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/port_types.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_cache.hpp"
#include "somasim/robot_ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::JointState;
using somasim::ObjectMotion;
using somasim::ObjectSpawn;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::SkinPart;
using somasim::SkinTaxels;
using somasim::Stimulus;
using somasim::testing::Harness;

namespace {

const std::string kRobot = std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";

std::string thrower(const std::string& params) {
  return "base_rate_hz: 20\nnodes:\n  t: {plugin: object_thrower, params: {robot: " + kRobot +
         ", parts: left_forearm" + (params.empty() ? "" : ", " + params) +
         "}, inputs: {taxels: harness.taxels, state: harness.state, objects: "
         "harness.objects}}\n";
}

SkinPart forearm() {
  SkinPart p;
  p.name = "left_forearm";
  p.link = "l_forearm";
  p.taxel_ids = {0, 1, 2};
  p.positions = {{0.1, -0.2, 0.3}, {0.12, -0.2, 0.3}, {0.1, -0.25, 0.28}};
  p.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, -1, 1).normalized(),
               Eigen::Vector3d::UnitX()};
  p.positions_link = p.positions;
  p.normals_link = p.normals;
  return p;
}

int dofs() {
  return somasim::robot::shared_robot_model(kRobot)->num_dofs();
}

void feed_world(Harness& h) {
  h.input<SkinTaxels>("taxels").parts = {forearm()};
  h.input<JointState>("state").position = Eigen::VectorXd::Zero(dofs());
  h.input<JointState>("state").velocity = Eigen::VectorXd::Zero(dofs());
}

// The object of the newest spawn request, where the world would have put it at `t` after spawn.
void feed_object(Harness& h, const ObjectSpawn& s, double t) {
  ObjectStates& o = h.input<ObjectStates>("objects");
  Eigen::Isometry3d pose = s.pose;
  pose.translation() += t * s.linear_velocity;
  o.names = {s.name};
  o.present = {true};
  o.poses = {pose};
  o.linear_velocity = {s.linear_velocity};
  o.angular_velocity = {Eigen::Vector3d::Zero()};
  o.radius = {s.size.x()};
}

// Step once, returning the stimulus pair after the object of the first spawn is fed.
std::pair<Stimulus, Stimulus> first_perception(Harness& h) {
  feed_world(h);
  EXPECT_TRUE(h.step());
  const auto& spawns = h.output<ObjectSpawns>("t.spawns").recent;
  EXPECT_EQ(spawns.size(), 1u);
  feed_object(h, spawns.back(), 0.05);
  EXPECT_TRUE(h.step());
  return {h.output<Stimulus>("t.stimulus"), h.output<Stimulus>("t.truth")};
}

std::vector<ObjectSpawn> all_spawns(Harness& h) {
  feed_world(h);
  std::vector<ObjectSpawn> out;
  std::uint64_t last = 0;
  while (h.step())
    for (const auto& s : h.output<ObjectSpawns>("t.spawns").recent)
      if (s.id > last) {
        last = s.id;
        out.push_back(s);
      }
  h.finish();
  return out;
}

std::string error_of(const std::string& yaml) {
  try {
    Harness h(yaml);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ObjectThrower, SpawnsMoveTowardTheAimedTaxelFromTheConeAtASpeedInRange) {
  Harness h(
      thrower("approaches: 12, pause: 0, size: 0.02, cone: 30, distance_min: 0.2, "
              "distance_max: 0.3, speed_min: 0.1, speed_max: 0.2, linger: 0.1"));
  const auto spawns = all_spawns(h);
  ASSERT_EQ(spawns.size(), 12u);
  EXPECT_EQ(h.metric("t", "approaches"), 12);
  const SkinPart part = forearm();
  int sphere = 0, box = 0;
  for (const auto& s : spawns) {
    EXPECT_EQ(s.motion, ObjectMotion::kKinematic);
    (s.shape == somasim::ObjectShape::kSphere ? sphere : box)++;
    const double speed = s.linear_velocity.norm();
    EXPECT_GE(speed, 0.1 - 1e-12);
    EXPECT_LE(speed, 0.2 + 1e-12);
    // The path ends at one of the taxels (centre one `size` above it, along its normal).
    const double travel = s.remove_after_s - 0.1;
    const Eigen::Vector3d end = s.pose.translation() + travel * s.linear_velocity;
    int aimed = -1;
    for (std::size_t k = 0; k < part.positions.size(); ++k)
      if ((end - (part.positions[k] + 0.02 * part.normals[k])).norm() < 1e-9)
        aimed = static_cast<int>(k);
    ASSERT_GE(aimed, 0) << "path ends at " << end.transpose();
    const Eigen::Vector3d from_target = s.pose.translation() - end;
    EXPECT_GE(from_target.norm(), 0.2 - 1e-9);
    EXPECT_LE(from_target.norm(), 0.3 + 1e-9);
    const double angle =
        std::acos(std::clamp(from_target.normalized().dot(part.normals[aimed]), -1.0, 1.0));
    EXPECT_LE(angle, 30.0 * M_PI / 180.0 + 1e-9);
    // Moving straight at the target.
    EXPECT_NEAR(s.linear_velocity.normalized().dot(-from_target.normalized()), 1.0, 1e-12);
  }
  EXPECT_EQ(sphere, 6);
  EXPECT_EQ(box, 6);
}

TEST(ObjectThrower, WithoutOffsetsOrNoiseTheStimulusIsTheTruth) {
  Harness h(thrower("approaches: 2"));
  const auto [seen, truth] = first_perception(h);
  ASSERT_TRUE(truth.present);
  ASSERT_TRUE(seen.present);
  EXPECT_LT((seen.position - truth.position).norm(), 1e-12);
  EXPECT_LT((seen.velocity - truth.velocity).norm(), 1e-12);
  EXPECT_EQ(seen.radius, truth.radius);
  const auto& spawn = h.output<ObjectSpawns>("t.spawns").recent.back();
  EXPECT_LT((truth.position - (spawn.pose.translation() + 0.05 * spawn.linear_velocity)).norm(),
            1e-12);
}

TEST(ObjectThrower, JointOffsetsMoveThePerceptionThroughTheBelievedLinkPose) {
  Harness h(thrower("approaches: 2, joint_offsets_deg: 'l_elbow: 10, l_shoulder_roll: -5'"));
  const auto [seen, truth] = first_perception(h);
  ASSERT_TRUE(seen.present);
  const auto model = somasim::robot::shared_robot_model(kRobot);
  somasim::robot::RobotData t(*model), b(*model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
  Eigen::VectorXd off = Eigen::VectorXd::Zero(model->num_dofs());
  off[model->dof_index("l_elbow")] = 10.0 * M_PI / 180.0;
  off[model->dof_index("l_shoulder_roll")] = -5.0 * M_PI / 180.0;
  somasim::robot::forward_kinematics(*model, t, q);
  somasim::robot::forward_kinematics(*model, b, q, off);
  const int link = model->link_index("l_forearm");
  const Eigen::Isometry3d m =
      somasim::robot::link_pose(b, link) * somasim::robot::link_pose(t, link).inverse();
  EXPECT_GT((seen.position - truth.position).norm(), 1e-3);
  EXPECT_LT((seen.position - m * truth.position).norm(), 1e-12);
  EXPECT_LT((seen.velocity - m.linear() * truth.velocity).norm(), 1e-12);
  EXPECT_NEAR(seen.velocity.norm(), truth.velocity.norm(), 1e-12);
}

TEST(ObjectThrower, NoiseIsAddedToThePerception) {
  Harness h(thrower("approaches: 2, position_noise: 0.01, velocity_noise: 0.01"));
  const auto [seen, truth] = first_perception(h);
  EXPECT_GT((seen.position - truth.position).norm(), 0.0);
  EXPECT_LT((seen.position - truth.position).norm(), 0.1);
  EXPECT_GT((seen.velocity - truth.velocity).norm(), 0.0);
}

TEST(ObjectThrower, UnknownJointInOffsetsSuggestsTheNearest) {
  const std::string msg = error_of(thrower("joint_offsets_deg: 'l_elbw: 3'"));
  EXPECT_NE(msg.find("node 't', key 'params.joint_offsets_deg': unknown joint 'l_elbw' (did you "
                     "mean 'l_elbow'?) (movable joints of the robot)"),
            std::string::npos)
      << msg;
}

TEST(ObjectThrower, UnknownPartNamesTheRobotsParts) {
  const std::string msg = error_of(
      "nodes:\n  t: {plugin: object_thrower, params: {robot: " + kRobot +
      ", parts: left_forarm}, inputs: {taxels: harness.taxels, state: harness.state, objects: "
      "harness.objects}}\n");
  EXPECT_NE(msg.find("node 't', key 'params.parts': unknown skin part 'left_forarm' (did you "
                     "mean 'left_forearm'?); the robot's skin parts: left_forearm, right_palm"),
            std::string::npos)
      << msg;
}

TEST(ObjectThrower, SameSeedSameSpawnsOtherSeedOthers) {
  auto trace = [](int seed) {
    somasim::LoadOptions o;
    o.seed = seed;
    Harness h(thrower("approaches: 3, pause: 0, speed_min: 0.15"), {}, o);
    std::vector<double> xs;
    for (const auto& s : all_spawns(h)) {
      for (int i = 0; i < 3; ++i) xs.push_back(s.pose.translation()[i]);
      xs.push_back(s.linear_velocity.norm());
    }
    return xs;
  };
  EXPECT_EQ(trace(4), trace(4));
  EXPECT_NE(trace(4), trace(5));
}
