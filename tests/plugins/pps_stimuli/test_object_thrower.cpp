// object_thrower: approach geometry, perceived stimulus without offsets or with noise,
// parameter errors, determinism. No physics: objects are fed by hand from the spawn requests.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "object_thrower_test_support.hpp"

using namespace object_thrower_test;
using somasim::ObjectMotion;

TEST(ObjectThrower, SpawnsMoveTowardTheAimedTaxelFromTheConeAtASpeedInRange) {
  Harness h(
      thrower("approaches: 12, pause: 0, size: 0.02, cone_deg: 30, distance_min: 0.2, "
              "distance_max: 0.3, speed_min: 0.1, speed_max: 0.2, linger: 0.1"));
  const auto spawns = all_spawns(h);
  ASSERT_EQ(spawns.size(), 12u);
  EXPECT_EQ(h.metric("t", "objects_presented"), 12);
  const SkinPart part = forearm();
  int sphere = 0, box = 0;
  for (const auto& s : spawns) {
    EXPECT_EQ(s.motion, ObjectMotion::kGuided);
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

TEST(ObjectThrower, NoiseIsAddedToThePerception) {
  Harness h(thrower("approaches: 2, position_noise: 0.01, velocity_noise: 0.01"));
  const auto [seen, truth] = first_perception(h);
  EXPECT_GT((seen.position - truth.position).norm(), 0.0);
  EXPECT_LT((seen.position - truth.position).norm(), 0.1);
  EXPECT_GT((seen.velocity - truth.velocity).norm(), 0.0);
}

TEST(ObjectThrower, UnknownPartNamesTheRobotsParts) {
  const std::string msg =
      error_of("robots: {icub: " + kRobot +
               "}\nnodes:\n  t: {plugin: object_thrower, params: {parts: left_forarm}, inputs: "
               "{taxels: harness.taxels, state: harness.state, objects: "
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
