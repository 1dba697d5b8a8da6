#pragma once
// The two eye cameras where the robot believes them: its encoder values plus an optional
// believed-kinematics error, through forward kinematics. Shared by the trackers.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/plugin.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class BelievedEyes {
 public:
  /// Declares the parameters `cameras` (two camera names of the robot model) and
  /// `joint_offsets_deg` ('joint: value, ...' [deg] added to the encoder values).
  static void declare_params(PluginSpec& spec);
  /// Reads those parameters for `model`; a camera not in the model or a bad offsets text is a
  /// located parameter error.
  void configure(NodeContext& ctx, std::shared_ptr<const robot::RobotModel> model);
  /// Both cameras (root frame) for the encoder values `encoders` [rad, m] (one per dof).
  std::vector<render::Camera> pose(const Eigen::VectorXd& encoders);
  /// Link poses (root frame) of the believed kinematics of the last pose() call.
  const std::vector<Eigen::Isometry3d>& link_poses() const { return data_->link_poses; }
  const std::vector<std::string>& names() const { return names_; }

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<robot::RobotData> data_;
  Eigen::VectorXd offsets_;
  std::vector<std::string> names_;
};

}  // namespace somasim::plugins
