#pragma once
// Vision through the believed head/eye kinematics (object_thrower): the cameras see the object
// where it truly is relative to the TRUE camera pose, and the robot places it in its root frame
// through the BELIEVED camera pose, so a point p [m, root] is perceived at
//   p' = T_cam_believed · T_cam_true⁻¹ · p,   a velocity v at v' = R_cam_believed · R_cam_trueᵀ · v
// (T_cam = pose of the vision link by forward kinematics; a fixed camera-in-link pose cancels).
#include <memory>

#include <Eigen/Geometry>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class BelievedVision {
 public:
  BelievedVision(std::shared_ptr<const robot::RobotModel> model, int vision_link);
  /// The root ← root map above for true and believed joint values (model dof order; RunError
  /// naming the input when a size is wrong).
  const Eigen::Isometry3d& update(const Eigen::VectorXd& q_true, const Eigen::VectorXd& q_believed);
  const Eigen::Isometry3d& transform() const { return transform_; }

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  int link_ = 0;
  robot::RobotData true_, believed_;
  Eigen::Isometry3d transform_ = Eigen::Isometry3d::Identity();
};

}  // namespace somasim::plugins
