// object_thrower: static and receding presentations, cylinders, the presentation output, start
// points and paths clear of the robot, bad lists and ranges (whole messages).
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "object_thrower_test_support.hpp"
#include "somasim/robot/clearance.hpp"

using namespace object_thrower_test;
using somasim::LinkPoses;
using somasim::ObjectMotion;
using somasim::ObjectShape;
using somasim::Presentation;
using somasim::PresentationMotion;

namespace {

// The taxel of forearm() whose target (taxel + size·n) is `from - distance·dir` for a
// direction within `cone_deg` of its normal and a distance in [lo, hi]; -1 if none.
int aimed_taxel(const Eigen::Vector3d& start, double size, double lo, double hi, double cone_deg) {
  const SkinPart part = forearm();
  for (std::size_t k = 0; k < part.positions.size(); ++k) {
    const Eigen::Vector3d rel = start - (part.positions[k] + size * part.normals[k]);
    const double angle = std::acos(std::clamp(rel.normalized().dot(part.normals[k]), -1.0, 1.0));
    if (rel.norm() >= lo - 1e-9 && rel.norm() <= hi + 1e-9 &&
        angle <= cone_deg * M_PI / 180.0 + 1e-9)
      return static_cast<int>(k);
  }
  return -1;
}

// Where the value of the third parameter (after robot and parts) starts on line 3.
std::string at_third_param() {
  return "<inline>:4:" + std::to_string(83);
}

}  // namespace

TEST(ObjectThrowerMotions, StaticObjectsStandStillInFrontOfATaxel) {
  Harness h(thrower(
      "motions: static, approaches: 6, pause: 0, size: 0.02, cone_deg: 30, distance_min: 0.1, "
      "distance_max: 0.2, static_duration: 1.5"));
  const auto spawns = all_spawns(h);
  ASSERT_EQ(spawns.size(), 6u);
  for (const auto& s : spawns) {
    EXPECT_EQ(s.linear_velocity, Eigen::Vector3d::Zero());
    EXPECT_DOUBLE_EQ(s.remove_after_s, 1.5);
    EXPECT_GE(aimed_taxel(s.pose.translation(), 0.02, 0.1, 0.2, 30), 0)
        << s.pose.translation().transpose();
  }
  EXPECT_EQ(h.metric("t", "presented_per_motion"), nlohmann::json({{"static", 6}}));
}

TEST(ObjectThrowerMotions, RecedingObjectsMoveAwayFromATaxelForDistanceMax) {
  Harness h(thrower(
      "motions: receding, approaches: 6, pause: 0, size: 0.02, cone_deg: 30, receding_start_min: "
      "0.03, receding_start_max: 0.06, distance_max: 0.25, speed_min: 0.1, speed_max: 0.2"));
  const auto spawns = all_spawns(h);
  ASSERT_EQ(spawns.size(), 6u);
  const SkinPart part = forearm();
  for (const auto& s : spawns) {
    const int k = aimed_taxel(s.pose.translation(), 0.02, 0.03, 0.06, 30);
    ASSERT_GE(k, 0) << s.pose.translation().transpose();
    const Eigen::Vector3d out =
        (s.pose.translation() - (part.positions[k] + 0.02 * part.normals[k])).normalized();
    const double speed = s.linear_velocity.norm();
    EXPECT_GE(speed, 0.1 - 1e-12);
    EXPECT_LE(speed, 0.2 + 1e-12);
    EXPECT_NEAR(s.linear_velocity.normalized().dot(out), 1.0, 1e-12);  // straight away
    EXPECT_NEAR(s.remove_after_s * speed, 0.25, 1e-12);
  }
}

// Parts, shapes and motions each in turn with the presentation index.
TEST(ObjectThrowerMotions, PartsShapesAndMotionsCycleCylindersShowTheirSide) {
  Harness h(thrower(
      "parts: left_forearm right_palm, motions: approach static receding, shapes: sphere "
      "sphere cylinder cylinder, approaches: 12, pause: 0, size: 0.02, cylinder_half_height: 0.05, "
      "distance_max: 0.25, static_duration: 0.5"));
  feed_world(h);
  SkinPart palm = forearm();  // the same patch 1 m higher
  palm.name = "right_palm";
  palm.link = "r_hand";
  for (auto& p : palm.positions) p.z() += 1.0;
  h.input<SkinTaxels>("taxels").parts.push_back(palm);
  const auto spawns = all_spawns(h, /*feed=*/false);
  ASSERT_EQ(spawns.size(), 12u);
  const SkinPart part = forearm();
  for (std::size_t i = 0; i < spawns.size(); ++i) {
    const auto& s = spawns[i];
    EXPECT_EQ(s.pose.translation().z() > 0.9, i % 2 == 1) << i;  // the palm
    EXPECT_EQ(s.shape, i % 4 < 2 ? ObjectShape::kSphere : ObjectShape::kCylinder) << i;
    EXPECT_EQ(s.motion, ObjectMotion::kGuided);
    EXPECT_EQ(s.linear_velocity.isZero(), i % 3 == 1) << i;  // the static ones
    if (i % 3 == 2) {                                        // receding
      EXPECT_NEAR(s.remove_after_s * s.linear_velocity.norm(), 0.25, 1e-12) << i;
    }
    if (s.shape != ObjectShape::kCylinder) {
      EXPECT_EQ(s.size, Eigen::Vector3d(0.02, 0.0, 0.0));
      continue;
    }
    EXPECT_EQ(s.size, Eigen::Vector3d(0.02, 0.05, 0.0));
    // The cylinder axis is across the aimed taxel's normal (one of the three).
    double best = 1.0;
    for (const auto& n : part.normals)
      best = std::min(best, std::abs(n.dot(s.pose.linear().col(2))));
    EXPECT_LT(best, 1e-12);
  }
  EXPECT_EQ(h.metric("t", "presented_per_motion"),
            nlohmann::json({{"approach", 4}, {"static", 4}, {"receding", 4}}));
  EXPECT_EQ(h.metric("t", "objects_presented"), 12);
  EXPECT_EQ(h.metric("t", "presented_per_part"),
            nlohmann::json({{"left_forearm", {{"presentations", 6}}},
                            {"right_palm", {{"presentations", 6}}}}));
}

// A cube presented corner first: the corner (+1, +1, +1)·size points at the taxel and the
// centre stops sqrt(3)·size above it (the stimulus radius).
TEST(ObjectThrowerMotions, CubesCanMeetTheTaxelWithACorner) {
  Harness h(thrower("shapes: box, box_facing: corner, approaches: 3, pause: 0, size: 0.02"));
  feed_world(h);
  ASSERT_TRUE(h.step());
  const auto s = h.output<ObjectSpawns>("t.spawns").recent.back();
  const SkinPart part = forearm();
  const std::size_t k = std::size_t(h.output<Presentation>("t.presentation").taxel_id);
  const Eigen::Vector3d n = part.normals[k];
  EXPECT_EQ(s.shape, ObjectShape::kBox);
  EXPECT_EQ(s.size, Eigen::Vector3d::Constant(0.02));
  EXPECT_LT((s.pose.linear() * Eigen::Vector3d::Ones().normalized() + n).norm(), 1e-12);
  const double travel = s.remove_after_s - 0.1;
  const Eigen::Vector3d end = s.pose.translation() + travel * s.linear_velocity;
  EXPECT_LT((end - (part.positions[k] + std::sqrt(3.0) * 0.02 * n)).norm(), 1e-9);
  feed_object(h, s, 0.05);
  ASSERT_TRUE(h.step());
  EXPECT_DOUBLE_EQ(h.output<Stimulus>("t.stimulus").radius, std::sqrt(3.0) * 0.02);
  EXPECT_DOUBLE_EQ(h.output<Stimulus>("t.truth").radius, std::sqrt(3.0) * 0.02);
}

TEST(ObjectThrowerMotions, ThePresentationSaysWhatIsPresentedAndWhen) {
  Harness h(thrower(
      "motions: static receding, shapes: sphere, approaches: 2, pause: 0.5, static_duration: 1"));
  feed_world(h);
  ASSERT_TRUE(h.step());
  const Presentation& p = h.output<Presentation>("t.presentation");
  const auto first = h.output<ObjectSpawns>("t.spawns").recent.back();
  EXPECT_EQ(p.id, 1u);
  EXPECT_TRUE(p.active);
  EXPECT_EQ(p.motion, PresentationMotion::kStatic);
  EXPECT_EQ(p.object, first.name);
  EXPECT_EQ(p.body_part, "left_forearm");
  EXPECT_EQ(p.speed, 0.0);
  EXPECT_EQ(p.start_time_s, 0.0);
  const SkinPart part = forearm();
  const auto k = std::find(part.taxel_ids.begin(), part.taxel_ids.end(), p.taxel_id);
  ASSERT_NE(k, part.taxel_ids.end());
  EXPECT_EQ(p.aimed_point, part.positions[std::size_t(k - part.taxel_ids.begin())]);
  ASSERT_TRUE(h.step(19));  // t = 0.95 s: still there
  EXPECT_TRUE(p.active);
  ASSERT_TRUE(h.step());  // t = 1.0 s: removed, the pause runs
  EXPECT_FALSE(p.active);
  EXPECT_EQ(p.id, 1u);
  ASSERT_TRUE(h.step(10));  // t = 1.5 s: the next one
  EXPECT_TRUE(p.active);
  EXPECT_EQ(p.id, 2u);
  EXPECT_EQ(p.motion, PresentationMotion::kReceding);
  EXPECT_DOUBLE_EQ(p.start_time_s, 1.5);
  EXPECT_GT(p.speed, 0.0);
}

// Taxels on the real left forearm of the robot (arm raised as in pps_learn_objects): start
// points are tested against the robot's collision shapes when link_poses is wired.
TEST(ObjectThrowerMotions, StartPointsAreClearOfTheRobotForEveryMotion) {
  const auto model = somasim::robot::load_robot_model_shared(kRobot);
  somasim::robot::RobotData data(*model);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model->num_dofs());
  q[model->dof_index("l_shoulder_pitch")] = -40 * M_PI / 180;
  q[model->dof_index("l_shoulder_roll")] = 40 * M_PI / 180;
  q[model->dof_index("l_elbow")] = 60 * M_PI / 180;
  somasim::robot::forward_kinematics(*model, data, q);
  const Eigen::Isometry3d link = data.link_poses[std::size_t(model->link_index("l_forearm"))];
  const SkinPart part = forearm_ring(link, {90.0, 180.0, 270.0});
  const std::string params =
      "motions: static receding approach, shapes: sphere box, approaches: 30, pause: 0, size: "
      "0.02, cone_deg: 60, distance_min: 0.0, distance_max: 0.2, receding_start_min: 0.0, "
      "receding_start_max: 0.15, static_duration: 0.05";
  auto starts = [&](bool wired) {
    Harness h(thrower(params, wired ? "link_poses: harness.poses" : ""));
    feed_world(h);
    h.input<SkinTaxels>("taxels").parts = {part};
    if (wired) h.input<LinkPoses>("poses").poses = data.link_poses;
    return all_spawns(h, /*feed=*/false);
  };
  const int forearm_link = model->link_index("l_forearm");
  // The start clear of the robot, and the whole path (to where it is removed) clear of every
  // link but the forearm it is aimed at.
  auto clear = [&](const somasim::ObjectSpawn& s) {
    const double bound = s.shape == ObjectShape::kBox ? std::sqrt(3.0) * 0.02 : 0.02;
    const Eigen::Vector3d start = s.pose.translation();
    const Eigen::Vector3d end = start + std::max(0.0, s.remove_after_s - 0.1) * s.linear_velocity;
    return somasim::robot::point_clear_of_robot(*model, data.link_poses, start, bound + 0.01) &&
           somasim::robot::segment_clear_of_robot(*model, data.link_poses, start, end,
                                                  bound + 0.004, std::span(&forearm_link, 1));
  };
  int unclear_without = 0;
  for (const auto& s : starts(false)) unclear_without += clear(s) ? 0 : 1;
  EXPECT_GT(unclear_without, 5);  // the test would notice a missing check
  const auto spawns = starts(true);
  ASSERT_EQ(spawns.size(), 30u);
  for (const auto& s : spawns) EXPECT_TRUE(clear(s)) << s.pose.translation().transpose();
}

namespace {

// A part whose three taxels sit at the chest's centre facing up: no path reaches them.
struct InsideTheChest {
  std::shared_ptr<const somasim::robot::RobotModel> model =
      somasim::robot::load_robot_model_shared(kRobot);
  somasim::robot::RobotData data{*model};
  SkinPart part = forearm();
  InsideTheChest() {
    somasim::robot::forward_kinematics(*model, data, Eigen::VectorXd::Zero(model->num_dofs()));
    const Eigen::Isometry3d chest = data.link_poses[std::size_t(model->link_index("chest"))];
    for (std::size_t k = 0; k < 3; ++k) {
      part.positions[k] = chest.translation();
      part.normals[k] = Eigen::Vector3d::UnitZ();
    }
  }
};

}  // namespace

TEST(ObjectThrowerMotions, APartNoPathCanReachIsABadPresentationNamingWhatWasTried) {
  // Every taxel faces into the chest: the forearm pressed against the body, nothing reaches it.
  const InsideTheChest scene;
  const SkinPart& part = scene.part;
  const auto& data = scene.data;
  Harness h(
      thrower("approaches: 2, cone_deg: 10, wait_for_clear_path: 1", "link_poses: harness.poses"));
  feed_world(h);
  h.input<SkinTaxels>("taxels").parts = {part};
  h.input<LinkPoses>("poses").poses = data.link_poses;
  // Tried at t = 0, 0.5 and 1 s (20 Hz ticks), then given up.
  std::string msg;
  int steps = 0;
  try {
    while (steps < 100) {
      ++steps;
      h.step();
    }
  } catch (const somasim::RunError& e) {
    msg = e.what();
  }
  EXPECT_EQ(steps, 21);
  EXPECT_EQ(msg,
            "no path clear of the robot for a sphere (motion 'approach') aimed at 'left_forearm': "
            "50 taxels drawn, 100 paths each (start 0.2-0.3 m from the skin within 10 deg of its "
            "normal, the object 0.005 m clear of the other links); raise 'distance_min', lower "
            "'cone_deg' or 'size', or change the posture (waited 1 s for a clear path)");
}

TEST(ObjectThrowerMotions, APresentationWaitsForThePostureToClearItsPath) {
  // The taxels face into the chest for the first second, then the robot is elsewhere (its
  // links far below): the object is presented at the next retry, after two postponements.
  const InsideTheChest scene;
  const SkinPart& part = scene.part;
  const auto& data = scene.data;
  Harness h(thrower("approaches: 1, cone_deg: 10", "link_poses: harness.poses"));
  feed_world(h);
  h.input<SkinTaxels>("taxels").parts = {part};
  auto& poses = h.input<LinkPoses>("poses").poses;
  poses = data.link_poses;
  const auto& spawns = h.output<ObjectSpawns>("t.spawns").recent;
  while (h.time_s() < 0.9) {
    ASSERT_TRUE(h.step());
    EXPECT_TRUE(spawns.empty()) << h.time_s();
  }
  for (auto& pose : poses) pose.translation() += Eigen::Vector3d(0, 0, -5);
  while (spawns.empty()) ASSERT_TRUE(h.step());
  EXPECT_NEAR(h.time_s(), 1.05, 1e-9);  // launched at the retry at t = 1 s
  while (h.step()) {
  }
  h.finish();
  EXPECT_EQ(h.metric("t", "presentations_postponed"), 2);
}

TEST(ObjectThrowerMotions, BadListsAndRangesAreNamed) {
  EXPECT_EQ(error_of(thrower("motions: approach recedng")),
            at_third_param() +
                ": node 't', key 'params.motions': unknown motion 'recedng' (did you mean "
                "'receding'?); expected approach, static or receding");
  EXPECT_EQ(error_of(thrower("shapes: sphere cylindre")),
            "<inline>:4:" + std::to_string(82) +
                ": node 't', key 'params.shapes': unknown shape 'cylindre' (did you mean "
                "'cylinder'?); expected sphere, box or cylinder");
  EXPECT_EQ(error_of(thrower("receding_start_min: 0.2, receding_start_max: 0.1")),
            "<inline>:4:" + std::to_string(119) +
                ": node 't', key 'params.receding_start_max': must not be less than "
                "receding_start_min");
}
