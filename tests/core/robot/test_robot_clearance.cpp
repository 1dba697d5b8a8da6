// point_clear_of_robot: points inside or next to the robot are not clear; far points are.
#include <gtest/gtest.h>

#include "robot_test_support.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/kinematics.hpp"

using namespace somasim::robot;
using somasim::robot::test::load_icub;

namespace {
std::vector<Eigen::Isometry3d> rest_poses(const RobotModel& model) {
  RobotData data(model);
  forward_kinematics(model, data, Eigen::VectorXd::Zero(model.num_dofs()));
  return data.link_poses;
}
}  // namespace

TEST(RobotClearance, InsideTheHeadOrNextToTheForearmIsNotClear) {
  const RobotModel model = load_icub();
  const auto poses = rest_poses(model);
  const auto head = static_cast<std::size_t>(model.link_index("head"));
  // The head is a sphere of radius 0.055 m centred at (0.0628, 0.0108, 0) in its link frame.
  EXPECT_FALSE(
      point_clear_of_robot(model, poses, poses[head] * Eigen::Vector3d(0.06, 0.01, 0.0), 0.0));
  const auto forearm = static_cast<std::size_t>(model.link_index("l_forearm"));
  const Eigen::Vector3d beside = poses[forearm] * Eigen::Vector3d(0.0, -0.07, 0.03);
  EXPECT_FALSE(point_clear_of_robot(model, poses, beside, 0.01));
}

TEST(RobotClearance, FarAwayIsClearAndMarginsCount) {
  const RobotModel model = load_icub();
  const auto poses = rest_poses(model);
  EXPECT_TRUE(point_clear_of_robot(model, poses, Eigen::Vector3d(-1.0, 0.0, 0.3), 0.05));
  EXPECT_FALSE(point_clear_of_robot(model, poses, Eigen::Vector3d(-1.0, 0.0, 0.3), 1.5));
}

TEST(RobotClearance, WithoutPosesNothingIsTested) {
  const RobotModel model = load_icub();
  EXPECT_TRUE(point_clear_of_robot(model, {}, Eigen::Vector3d::Zero(), 0.1));
}
