#pragma once
// The two eye cameras where the robot believes them: its encoder values plus an optional
// believed-kinematics error, through forward kinematics. Shared by the trackers.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
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
  /// The inputs both trackers take: the two eyes' images and the encoders that pose them; a port
  /// block (somasim/plugin_ports.hpp) embedded first in their port structs.
  struct Inputs {
    In<RgbImage> left_eye_rgb;
    In<RgbImage> right_eye_rgb;
    In<JointState> joint_state;
    template <class V>
    void visit(V& v) {
      v.port("left_eye_rgb", left_eye_rgb,
             "rgb8 image of the first camera (e.g. cam.left_eye_rgb)");
      v.port("right_eye_rgb", right_eye_rgb,
             "rgb8 image of the second camera (e.g. cam.right_eye_rgb)");
      v.port("joint_state", joint_state,
             "encoder values: the head and eye joints pose the cameras (e.g. world.joint_state)");
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
