// camera_sight: points on the optical axis project to the principal point and are seen; points
// behind the camera, outside the image or behind the robot's own forearm are not, each for its
// reason.
#include <gtest/gtest.h>

#include "robot_test_support.hpp"
#include "somasim/robot/camera_view.hpp"
#include "somasim/robot/kinematics.hpp"

using namespace somasim::robot;
using somasim::robot::test::kDeg;
using somasim::robot::test::load_icub;

namespace {

// The visual PPS posture (arms raised in front), the head turned down to the left forearm.
std::vector<Eigen::Isometry3d> looking_at_the_arms(const RobotModel& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_dofs());
  const std::pair<const char*, double> posture[] = {
      {"l_shoulder_pitch", -60}, {"l_shoulder_roll", 40}, {"l_shoulder_yaw", 45},
      {"l_elbow", 55},           {"l_wrist_prosup", -45}, {"r_shoulder_pitch", -45},
      {"r_shoulder_roll", 40},   {"r_shoulder_yaw", 30},  {"r_elbow", 70},
      {"neck_pitch", -40},       {"neck_yaw", 25},        {"eyes_tilt", -25}};
  for (const auto& [joint, deg] : posture) q[model.dof_index(joint)] = deg * kDeg;
  RobotData data(model);
  forward_kinematics(model, data, q);
  return data.link_poses;
}

const Camera& left_eye(const RobotModel& model) {
  return model.cameras()[static_cast<std::size_t>(model.find_camera("left_eye"))];
}

}  // namespace

TEST(CameraView, TheOpticalAxisProjectsToThePrincipalPoint) {
  const RobotModel model = load_icub();
  const auto poses = looking_at_the_arms(model);
  const Camera& eye = left_eye(model);
  const Eigen::Isometry3d pose = camera_pose(eye, poses);
  const Eigen::Vector3d ahead = pose * Eigen::Vector3d(0.0, 0.0, 0.4);
  const auto uv = project_point(eye, pose, ahead);
  ASSERT_TRUE(uv.has_value());
  EXPECT_NEAR(uv->x(), eye.cx, 1e-9);
  EXPECT_NEAR(uv->y(), eye.cy, 1e-9);
  // 0.1 m right and down of the axis at 0.4 m: fx·0.25 px right, fy·0.25 px down.
  const auto off = project_point(eye, pose, pose * Eigen::Vector3d(0.1, 0.1, 0.4));
  ASSERT_TRUE(off.has_value());
  EXPECT_NEAR(off->x(), eye.cx + 0.25 * eye.fx, 1e-9);
  EXPECT_NEAR(off->y(), eye.cy + 0.25 * eye.fy, 1e-9);
}

TEST(CameraView, EachReasonForNotSeeing) {
  const RobotModel model = load_icub();
  const auto poses = looking_at_the_arms(model);
  const Camera& eye = left_eye(model);
  const Eigen::Isometry3d pose = camera_pose(eye, poses);
  EXPECT_FALSE(project_point(eye, pose, pose * Eigen::Vector3d(0, 0, -0.3)).has_value());
  EXPECT_EQ(camera_sight(model, poses, eye, pose * Eigen::Vector3d(0, 0, -0.3), 0), Sight::kBehind);
  EXPECT_EQ(camera_sight(model, poses, eye, pose * Eigen::Vector3d(0.5, 0, 0.3), 0),
            Sight::kOutOfImage);
  // A margin narrows the image: a point 5 px inside the border is out with a 10 px margin.
  const double u = eye.width - 0.5 - 5.0;
  const Eigen::Vector3d near_border = pose * Eigen::Vector3d((u - eye.cx) / eye.fx * 0.4, 0.0, 0.4);
  EXPECT_EQ(camera_sight(model, poses, eye, near_border, 0), Sight::kSeen);
  EXPECT_EQ(camera_sight(model, poses, eye, near_border, 10), Sight::kOutOfImage);
  EXPECT_EQ(camera_sight(model, {}, eye, near_border, 0), Sight::kBehind);
}

TEST(CameraView, TheFarSideOfTheForearmIsHiddenItsNearSideSeen) {
  const RobotModel model = load_icub();
  const auto poses = looking_at_the_arms(model);
  const Camera& eye = left_eye(model);
  const Eigen::Vector3d centre = camera_pose(eye, poses).translation();
  const auto forearm = static_cast<std::size_t>(model.link_index("l_forearm"));
  const auto& shape = model.link(static_cast<int>(forearm)).collision.front();
  const Eigen::Vector3d middle = poses[forearm] * shape.origin.translation();
  const Eigen::Vector3d away = (middle - centre).normalized();
  EXPECT_EQ(camera_sight(model, poses, eye, middle + 0.12 * away, 0), Sight::kHiddenByBody);
  EXPECT_EQ(camera_sight(model, poses, eye, middle - 0.12 * away, 0), Sight::kSeen);
}
