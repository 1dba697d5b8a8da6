#pragma once
/// @file
/// Kinematics over the whole tree as free functions (model, data, ...), Pinocchio style.
/// Nothing here allocates once RobotData exists.
///
/// Frames: poses and Jacobians are in the root frame (iCub: x backward, y right, z up).
/// Units: [m], [rad]. Jacobians are 6 × num_dofs: rows 0-2 linear velocity [m/s per unit q̇],
/// rows 3-5 angular velocity [rad/s per unit q̇] of a point fixed to a link.
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// Per-use state of a RobotModel. Sized once from the model; reused across calls.
struct RobotData {
  explicit RobotData(const RobotModel& model);

  Eigen::VectorXd q;        ///< joint values used by the last forward_kinematics [rad]/[m]
  Eigen::VectorXd offsets;  ///< per-dof offsets added to q (e.g. body-schema β), default 0
  std::vector<Eigen::Isometry3d> link_poses;   ///< in the root frame
  std::vector<Eigen::Vector3d> joint_axes;     ///< per joint: world axis [unit]
  std::vector<Eigen::Vector3d> joint_origins;  ///< per joint: a world point on the axis [m]
};

/// Computes every link pose for joint values q (size num_dofs) plus data.offsets.
/// InputError when q has the wrong size ("expected N joint values, got M").
void forward_kinematics(const RobotModel& model, RobotData& data,
                        const Eigen::Ref<const Eigen::VectorXd>& q);
/// Same, with explicit per-dof offsets (stored into data.offsets).
void forward_kinematics(const RobotModel& model, RobotData& data,
                        const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& offsets);

/// Pose of a link or a frame in the root frame (after forward_kinematics).
inline Eigen::Isometry3d link_pose(const RobotData& data, int link) {
  return data.link_poses[link];
}
inline Eigen::Isometry3d frame_pose(const RobotData& data, const FrameRef& frame) {
  return data.link_poses[frame.link] * frame.pose;
}

/// Geometric Jacobian (6 × num_dofs, root frame) of the point `point_in_link` [m, link frame]
/// fixed to `link`, after forward_kinematics. Columns of dofs not moving the link are zero.
void point_jacobian(const RobotModel& model, const RobotData& data, int link,
                    const Eigen::Vector3d& point_in_link, Eigen::Ref<Matrix6Xd> jacobian);
/// Jacobian of a frame's origin (its angular rows are the link's angular velocity).
inline void frame_jacobian(const RobotModel& model, const RobotData& data, const FrameRef& frame,
                           Eigen::Ref<Matrix6Xd> jacobian) {
  point_jacobian(model, data, frame.link, frame.pose.translation(), jacobian);
}

/// The iCub's coupled eyes: the head encoders give version and vergence [rad]; the pan joints
/// are left = version + vergence/2, right = version − vergence/2.
struct EyePans {
  double left = 0.0;
  double right = 0.0;
};
inline EyePans eye_pans(double version, double vergence) {
  return {version + 0.5 * vergence, version - 0.5 * vergence};
}
/// Inverse of eye_pans: {version, vergence} from the two pan angles.
inline std::pair<double, double> version_vergence(const EyePans& pans) {
  return {0.5 * (pans.left + pans.right), pans.left - pans.right};
}

}  // namespace somasim::robot
