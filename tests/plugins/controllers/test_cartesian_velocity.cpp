// cartesian_velocity: integrating the commanded joint velocities moves the chosen point (hand or
// forearm) along the commanded direction at the commanded speed (checked with forward
// kinematics); joint and velocity limits; orientation hold; base/tip chains; errors.
#include <cmath>

#include <gtest/gtest.h>

#include "kinematic_world.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/testing/harness.hpp"

using somasim::JointCommand;
using somasim::JointCommandMode;
using somasim::JointState;
using somasim::testing::Harness;
using somasim::testing::KinematicWorld;

namespace {

constexpr double kRate = 100.0;
constexpr double kDeg = M_PI / 180.0;

std::string graph(const std::string& params) {
  return "base_rate_hz: 100\nrobots: {icub: " + somasim::testing::icub_path() +
         "}\nnodes:\n  cv: {plugin: cartesian_velocity, params: {" + params +
         "}, inputs: {state: harness.state, velocity: harness.v}}\n";
}

// Root-frame position of `point` on `link` for the world's joints.
Eigen::Vector3d point_at(const KinematicWorld& w, const std::string& link,
                         const Eigen::Vector3d& point) {
  somasim::robot::RobotData data(*w.model);
  somasim::robot::forward_kinematics(*w.model, data, w.state.position);
  return data.link_poses[w.model->link_index(link)] * point;
}
Eigen::Matrix3d link_rotation(const KinematicWorld& w, const std::string& link) {
  somasim::robot::RobotData data(*w.model);
  somasim::robot::forward_kinematics(*w.model, data, w.state.position);
  return data.link_poses[w.model->link_index(link)].linear();
}

// Runs `ticks` control steps with the kinematic world in the loop.
void run(Harness& h, KinematicWorld& world, const Eigen::Vector3d& v, int ticks) {
  for (int k = 0; k < ticks; ++k) {
    h.input<JointState>("state") = world.state;
    h.input<Eigen::Vector3d>("v") = v;
    ASSERT_TRUE(h.step());
    world.apply(h.output<JointCommand>("cv.command"));
  }
}

// Moves the point for 1 s at `v` and checks the displacement against v · 1 s.
void expect_moves_along(const std::string& params, const std::string& link,
                        const Eigen::Vector3d& point, const Eigen::Vector3d& v) {
  KinematicWorld world(1.0 / kRate);
  Harness h(graph(params));
  const Eigen::Vector3d p0 = point_at(world, link, point);
  run(h, world, v, 1);
  EXPECT_NEAR((h.output<Eigen::Vector3d>("cv.point") - p0).norm(), 0.0, 1e-12);
  // Away from singularities and limits the command reproduces v exactly (no damping bias).
  EXPECT_NEAR((h.output<Eigen::Vector3d>("cv.point_velocity") - v).norm(), 0.0, 1e-9);
  EXPECT_EQ(h.output<double>("cv.limited"), 0.0);
  run(h, world, v, 99);
  const Eigen::Vector3d moved = point_at(world, link, point) - p0;
  const Eigen::Vector3d dir = v.normalized();
  EXPECT_NEAR(moved.dot(dir), v.norm(), 0.002) << moved.transpose();  // speed, within 2 mm / s
  EXPECT_LT((moved - moved.dot(dir) * dir).norm(), 0.002) << moved.transpose();  // direction
}

}  // namespace

TEST(CartesianVelocity, MovesThePalmAlongTheCommandedDirection) {
  // Default point: the chain's tip link origin; here an explicit point on the palm.
  expect_moves_along("chain: right_arm, link: r_hand, point: [-0.03, 0, 0]", "r_hand",
                     {-0.03, 0, 0}, {0.0, 0.03, 0.04});
  expect_moves_along("chain: right_arm, link: r_hand, point: [-0.03, 0, 0]", "r_hand",
                     {-0.03, 0, 0}, {-0.05, 0, 0});
}

TEST(CartesianVelocity, MovesAPointOnTheForearmNotOnlyTheHand) {
  const std::string params = "chain: right_arm, link: r_forearm, point: [0, 0.07, 0.02]";
  expect_moves_along(params, "r_forearm", {0, 0.07, 0.02}, {0.0, 0.0, 0.05});
  expect_moves_along(params, "r_forearm", {0, 0.07, 0.02}, {0.04, -0.02, 0.0});
  // Joints after the forearm cannot move that point: they are not commanded to move.
  KinematicWorld world(1.0 / kRate);
  Harness h(graph(params));
  run(h, world, {0, 0, 0.05}, 1);
  const auto& c = h.output<JointCommand>("cv.command");
  EXPECT_EQ(c.velocity[world.dof("r_wrist_pitch")], 0.0);
  EXPECT_EQ(c.velocity[world.dof("r_wrist_yaw")], 0.0);
}

TEST(CartesianVelocity, CommandsVelocityModeOnTheChainDofsOnly) {
  KinematicWorld world(1.0 / kRate);
  Harness h(graph("base: chest, tip: r_palm"));  // the arm without the torso
  run(h, world, {0, 0, 0.05}, 1);
  const auto& c = h.output<JointCommand>("cv.command");
  for (int d = 0; d < world.model->num_dofs(); ++d) {
    const std::string& name = world.model->joint(world.model->dof_joint(d)).name;
    const bool arm =
        name.rfind("r_shoulder", 0) == 0 || name == "r_elbow" || name.rfind("r_wrist", 0) == 0;
    EXPECT_EQ(c.mode[d], arm ? JointCommandMode::kVelocity : JointCommandMode::kNone) << name;
  }
}

TEST(CartesianVelocity, StaysWithinTheJointLimitsWhenDrivenOutOfReach) {
  KinematicWorld world(1.0 / kRate);
  Harness h(graph("chain: right_arm, limit_margin_deg: 2"));
  const Eigen::Vector3d p0 = point_at(world, "r_hand", Eigen::Vector3d::Zero());
  const Eigen::Vector3d v(0.0, 0.1, 0.05);  // 1.1 m in 10 s: far out of reach
  bool limited = false;
  for (int k = 0; k < 1000; ++k) {
    run(h, world, v, 1);
    limited = limited || h.output<double>("cv.limited") == 1.0;
    for (int d : {world.dof("r_shoulder_pitch"), world.dof("r_shoulder_roll"),
                  world.dof("r_shoulder_yaw"), world.dof("r_elbow"), world.dof("r_wrist_prosup"),
                  world.dof("r_wrist_pitch"), world.dof("r_wrist_yaw"), world.dof("torso_yaw"),
                  world.dof("torso_roll"), world.dof("torso_pitch")}) {
      ASSERT_GE(world.state.position[d], world.model->lower_limits()[d] + 2 * kDeg - 1e-9) << k;
      ASSERT_LE(world.state.position[d], world.model->upper_limits()[d] - 2 * kDeg + 1e-9) << k;
    }
  }
  EXPECT_TRUE(limited);
  // It still went as far as it could in the commanded direction.
  EXPECT_GT((point_at(world, "r_hand", Eigen::Vector3d::Zero()) - p0).dot(v.normalized()), 0.1);
  EXPECT_EQ(h.finish(), "");
  EXPECT_GT(h.metric("cv", "limited_fraction").get<double>(), 0.0);
}

TEST(CartesianVelocity, VelocityLimitsSlowDownButKeepTheDirection) {
  KinematicWorld world(1.0 / kRate);
  Harness h(graph("chain: right_arm, max_joint_velocity_deg: [3]"));
  const Eigen::Vector3d v(0.0, 0.0, 0.2);
  for (int k = 0; k < 20; ++k) {
    run(h, world, v, 1);
    const auto& c = h.output<JointCommand>("cv.command");
    for (int d = 0; d < world.model->num_dofs(); ++d)
      ASSERT_LE(std::abs(c.velocity[d]), 3 * kDeg + 1e-12);
    const Eigen::Vector3d pv = h.output<Eigen::Vector3d>("cv.point_velocity");
    EXPECT_EQ(h.output<double>("cv.limited"), 1.0);
    EXPECT_LT(pv.norm(), 0.2);
    EXPECT_GT(pv.norm(), 0.0);
    EXPECT_NEAR(pv.normalized().dot(v.normalized()), 1.0, 1e-9);
  }
}

TEST(CartesianVelocity, PerJointVelocityLimits) {
  KinematicWorld world(1.0 / kRate);
  Harness h(
      graph("chain: right_arm, max_joint_velocity_deg: [1, 1, 1, 10, 10, 10, 10, 10, 10, 10]"));
  run(h, world, {0.0, 0.0, 0.2}, 1);
  const auto& c = h.output<JointCommand>("cv.command");
  for (const char* torso : {"torso_pitch", "torso_roll", "torso_yaw"})
    EXPECT_LE(std::abs(c.velocity[world.dof(torso)]), 1 * kDeg + 1e-12) << torso;
}

TEST(CartesianVelocity, HoldsTheLinkOrientationWhenAsked) {
  KinematicWorld world(1.0 / kRate);
  Harness h(graph("chain: right_arm, hold_orientation: true"));
  const Eigen::Matrix3d r0 = link_rotation(world, "r_hand");
  const Eigen::Vector3d p0 = point_at(world, "r_hand", Eigen::Vector3d::Zero());
  run(h, world, {0.0, 0.0, 0.04}, 100);
  const Eigen::AngleAxisd turned(r0.transpose() * link_rotation(world, "r_hand"));
  EXPECT_LT(std::abs(turned.angle()), 0.5 * kDeg);
  EXPECT_NEAR((point_at(world, "r_hand", Eigen::Vector3d::Zero()) - p0).z(), 0.04, 0.002);
  // Without the hold the hand turns for the same motion.
  KinematicWorld free_world(1.0 / kRate);
  Harness free(graph("chain: right_arm"));
  run(free, free_world, {0.0, 0.0, 0.04}, 100);
  const Eigen::AngleAxisd free_turn(r0.transpose() * link_rotation(free_world, "r_hand"));
  EXPECT_GT(std::abs(free_turn.angle()), 1.0 * kDeg);
}

TEST(CartesianVelocity, ALinkNotInTheChainIsABadInput) {
  try {
    Harness h(graph("chain: right_arm, link: l_forearm"));
    FAIL() << "expected an InputError";
  } catch (const somasim::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(
        m.substr(m.find("node")),
        "node 'cv', key 'params.link': link 'l_forearm' is not in chain 'right_arm' "
        "(links: torso_1, torso_2, chest, r_shoulder_1, r_shoulder_2, r_upper_arm, r_elbow_1, "
        "r_forearm, r_wrist_1, r_hand, left_arm_2, left_eye_2)");
  }
}

TEST(CartesianVelocity, ChainParameterErrors) {
  const auto error_of = [](const std::string& params) -> std::string {
    try {
      Harness h(graph(params));
      return "no error";
    } catch (const somasim::InputError& e) {
      const std::string m = e.what();
      return m.substr(m.find("node"));
    }
  };
  EXPECT_EQ(error_of("chain: rigth_arm"),
            "node 'cv', key 'params.chain': robot 'icub_v1': unknown chain 'rigth_arm' (did you "
            "mean 'right_arm'?)");
  EXPECT_EQ(error_of("chain: right_arm, tip: r_palm"),
            "node 'cv', key 'params.tip': give either `chain` or `tip` (and `base`), not both");
  EXPECT_EQ(error_of("link: r_hand"),
            "node 'cv', key 'params.chain': expected a chain: give `chain` (a named chain of the "
            "robot) or `tip` (and optionally `base`)");
  EXPECT_EQ(error_of("chain: right_arm, base: chest"),
            "node 'cv', key 'params.base': `base` goes with `tip`, not with `chain`");
  EXPECT_EQ(error_of("chain: right_arm, link: r_hnd"),
            "node 'cv', key 'params.link': robot 'icub_v1': unknown link 'r_hnd' (did you mean "
            "'r_hand'?)");
  EXPECT_EQ(error_of("chain: right_arm, max_joint_velocity_deg: [10, 20]"),
            "node 'cv', key 'params.max_joint_velocity_deg': max joint velocity: expected 1 or 10 "
            "values (one per joint of chain 'right_arm'), got 2");
}
