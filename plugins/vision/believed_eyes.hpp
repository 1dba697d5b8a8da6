#pragma once
// The two eye cameras where the robot believes them: its encoder values plus an optional
// believed-kinematics error, through forward kinematics. Shared by the trackers.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class BelievedEyes {
 public:
  /// The parameters: a config block (somasim/config.hpp) embedded in the trackers' configs.
  struct Config {
    std::vector<std::string> cameras{"left_eye", "right_eye"};  ///< two cameras of the model
    std::string joint_offsets_deg;  ///< 'joint: value, ...' [deg] added to the encoder values
    template <class V>
    void visit(V& v) {
      v.field("cameras", cameras)
          .size(2)
          .doc(
              "the robot model's cameras whose images arrive on left_eye_rgb and right_eye_rgb "
              "(their intrinsics are the calibration the images must match)");
      v.field("joint_offsets_deg", joint_offsets_deg)
          .map_as_text()
          .doc(
              "believed-kinematics error, 'joint: value, ...' [deg] added to the encoder values "
              "before the cameras are posed (as proprioception's joint_offsets_deg)");
    }
  };
  /// Sets up `config` for `model`; a camera not in the model or a bad offsets text is a
  /// located parameter error.
  void configure(const NodeContext& ctx, const Config& config,
                 std::shared_ptr<const robot::RobotModel> model);
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
