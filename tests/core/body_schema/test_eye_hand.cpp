// Eye-hand kinematics: palm poses in the left-eye frame, nominal IK to them and the visual-
// servoing step converging with and without offsets in the model.
#include <gtest/gtest.h>

#include <numbers>

#include "real_arm_views.hpp"
#include "somasim/body_schema/eye_hand.hpp"
#include "somasim/body_schema/pose_error.hpp"

namespace somasim::body_schema {
namespace {

using testing::arm_dofs;
using testing::icub;

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::VectorXd offsets_rad(const Eigen::Matrix<double, 7, 1>& deg) {
  Eigen::VectorXd o = Eigen::VectorXd::Zero(icub()->num_dofs());
  const std::vector<int> dofs = arm_dofs();
  for (std::size_t j = 0; j < dofs.size(); ++j)
    o[dofs[j]] = deg[static_cast<Eigen::Index>(j)] * kDeg;
  return o;
}

TEST(EyeHand, PoseErrorIsPositionAndRotationVector) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = Eigen::Isometry3d::Identity();
  a.translation() = Eigen::Vector3d(0.01, 0, 0);
  a.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Vector6d e = pose_error(a, b);
  EXPECT_NEAR((e.head<3>() - Eigen::Vector3d(0.01, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((e.tail<3>() - Eigen::Vector3d(0, 0, 0.2)).norm(), 0.0, 1e-12);
}

TEST(EyeHand, PalmPoseFromLinkPosesEqualsTheKinematicOne) {
  EyeHand eh(icub(), "left_eye", "r_palm", "chest");
  const Eigen::VectorXd q = testing::hand_before_eyes();
  robot::RobotData data(*icub());
  robot::forward_kinematics(*icub(), data, q);
  const Eigen::Isometry3d a = eh.palm_eye(q, Eigen::VectorXd::Zero(q.size()));
  const Eigen::Isometry3d b = eh.palm_eye(data.link_poses);
  EXPECT_LT(position_error_mm(a, b), 1e-9);
  EXPECT_GT(a.translation().z(), 0.1);  // in front of the eye
}

TEST(EyeHand, NominalIkReachesAPalmPoseOfAnotherPosture) {
  EyeHand eh(icub(), "left_eye", "r_palm", "chest");
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(icub()->num_dofs());
  Eigen::VectorXd goal = testing::hand_before_eyes();
  goal[icub()->dof_index("r_elbow")] += 15 * kDeg;
  goal[icub()->dof_index("r_wrist_pitch")] -= 10 * kDeg;
  const Eigen::Isometry3d target = eh.palm_eye(goal, zero);
  Eigen::VectorXd q = testing::hand_before_eyes();
  const robot::IkResult r = eh.solve(target, q);
  EXPECT_TRUE(r.success);
  const Eigen::Isometry3d reached = eh.palm_eye(q, zero);
  EXPECT_LT(position_error_mm(reached, target), 0.2);
  EXPECT_LT(orientation_error_deg(reached.linear(), target.linear()), 0.1);
}

TEST(EyeHand, ServoingConvergesOnTheModelItIsGiven) {
  EyeHand eh(icub(), "left_eye", "r_palm", "chest");
  const Eigen::VectorXd beta = offsets_rad(testing::true_offsets_deg());
  for (const Eigen::VectorXd& model_offsets :
       {Eigen::VectorXd(Eigen::VectorXd::Zero(beta.size())), beta}) {
    Eigen::VectorXd goal = testing::hand_before_eyes();
    goal[icub()->dof_index("r_shoulder_yaw")] += 8 * kDeg;
    goal[icub()->dof_index("r_wrist_prosup")] -= 10 * kDeg;
    const Eigen::Isometry3d target = eh.palm_eye(goal, model_offsets);
    Eigen::VectorXd q = testing::hand_before_eyes();
    const double before = position_error_mm(eh.palm_eye(q, model_offsets), target);
    for (int k = 0; k < 50; ++k) q = eh.servo_step(q, model_offsets, target, 5.0, 0.1);
    const Eigen::Isometry3d reached = eh.palm_eye(q, model_offsets);
    EXPECT_GT(before, 20.0);
    EXPECT_LT(position_error_mm(reached, target), 0.1);
    EXPECT_LT(orientation_error_deg(reached.linear(), target.linear()), 0.05);
  }
}

}  // namespace
}  // namespace somasim::body_schema
