#include "believed_eyes.hpp"

#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/joint_text.hpp"

namespace somasim::plugins {

void BelievedEyes::declare_params(PluginSpec& spec) {
  spec.add_string_list("cameras")
      .size(2)
      .defaults(std::vector<std::string>{"left_eye", "right_eye"})
      .describe(
          "the robot model's cameras whose images arrive on left_eye_rgb and right_eye_rgb (their "
          "intrinsics are the calibration the images must match)");
  spec.add_string("joint_offsets_deg")
      .accepts_map_as_text()
      .defaults(std::string(""))
      .describe(
          "believed-kinematics error, 'joint: value, ...' [deg] added to the encoder values "
          "before the cameras are posed (as proprioception's joint_offsets_deg)");
}

void BelievedEyes::configure(NodeContext& ctx, std::shared_ptr<const robot::RobotModel> model) {
  model_ = std::move(model);
  data_ = std::make_unique<robot::RobotData>(*model_);
  try {
    offsets_ = robot::parse_joint_offsets(*model_, ctx.param<std::string>("joint_offsets_deg"));
  } catch (const InputError& e) {
    ctx.param_error("joint_offsets_deg", e.what());
  }
  names_ = ctx.param<std::vector<std::string>>("cameras");
  robot::forward_kinematics(*model_, *data_, Eigen::VectorXd::Zero(model_->num_dofs()));
  for (const std::string& c : names_) {
    try {
      render::camera_for(*model_, c, data_->link_poses);
    } catch (const InputError& e) {
      ctx.param_error("cameras", e.what());
    }
  }
}

std::vector<render::Camera> BelievedEyes::pose(const Eigen::VectorXd& encoders) {
  robot::forward_kinematics(*model_, *data_, encoders + offsets_);
  return {render::camera_for(*model_, names_[0], data_->link_poses),
          render::camera_for(*model_, names_[1], data_->link_poses)};
}

}  // namespace somasim::plugins
