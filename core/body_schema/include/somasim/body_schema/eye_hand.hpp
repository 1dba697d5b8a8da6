#pragma once
/// @file
/// Eye-hand kinematics of the body-schema study: the palm pose in the left-eye frame
/// K(θ + β), its Jacobian over the arm joints in that frame, inverse kinematics of the nominal
/// model to a desired palm pose, and the position-based visual-servoing step
/// q̇ = −λ J⁺(θ + β̂) e (Vicente et al. 2016, eqs 28–31).
///
/// Frames: the eye frame is the robot model camera's frame (x right, y down, z optical axis);
/// poses [m], joint values [rad] in model dof order (full vectors), offsets likewise (0 for
/// joints without one). The head is calibrated: the eye pose comes from the encoders alone.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/inverse_kinematics.hpp"
#include "somasim/robot/kinematic_chain.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::body_schema {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// 6-D pose error e = [p_a − p_b ; θ·axis of R_a R_bᵀ] (position [m], rotation vector [rad]),
/// both poses in the same frame.
Vector6d pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

class EyeHand {
 public:
  /// `camera`: the model camera of the eye frame; `palm`: a frame or link; `arm_base`: the link
  /// the arm chain starts from (its joints are the ones moved). InputError for unknown names.
  EyeHand(std::shared_ptr<const robot::RobotModel> model, const std::string& camera,
          const std::string& palm, const std::string& arm_base);

  /// Pose of the palm in the eye frame for joint values q plus offsets.
  Eigen::Isometry3d palm_eye(const Eigen::VectorXd& q, const Eigen::VectorXd& offsets);
  /// Pose of the eye (camera) in the root frame for joint values q.
  Eigen::Isometry3d eye_root(const Eigen::VectorXd& q);
  /// Palm pose in the eye frame from measured link poses (root <- link, e.g. the world's).
  Eigen::Isometry3d palm_eye(const std::vector<Eigen::Isometry3d>& link_poses) const;

  /// Nominal IK (β = 0): arm joints moving the palm to `target_eye`; q holds the other joints
  /// and the initial guess, and receives the solution. Returns the IK result (errors of the
  /// best pose found).
  robot::IkResult solve(const Eigen::Isometry3d& target_eye, Eigen::VectorXd& q);

  /// One servo step of `dt` [s]: the joint values to command so that the palm (model with
  /// `offsets`) moves toward `target_eye` with e decaying at rate `gain` [1/s]; within limits.
  Eigen::VectorXd servo_step(const Eigen::VectorXd& q, const Eigen::VectorXd& offsets,
                             const Eigen::Isometry3d& target_eye, double gain, double dt);

  /// Model dof index of each arm joint (base to palm).
  const std::vector<int>& arm_dofs() const { return chain_.dof_indices(); }
  const robot::RobotModel& model() const { return *model_; }

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  int camera_link_;
  Eigen::Isometry3d camera_pose_;  // camera frame in its link
  robot::FrameRef palm_;
  int base_link_;
  robot::KinematicChain chain_;
  robot::IkSolver ik_;
  robot::RobotData data_;
  robot::Matrix6Xd jacobian_;
};

}  // namespace somasim::body_schema
