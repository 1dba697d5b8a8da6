#include "believed_eyes.hpp"

#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/joint_text.hpp"

namespace somasim::plugins {

void BelievedEyes::configure(const NodeContext& ctx, const Config& config,
                             std::shared_ptr<const robot::RobotModel> model) {
  model_ = std::move(model);
  data_ = std::make_unique<robot::RobotData>(*model_);
  try {
    offsets_ = robot::parse_joint_offsets(*model_, config.joint_offsets_deg);
  } catch (const InputError& e) {
    config_error(ctx, config, config.joint_offsets_deg, e.what());
  }
  names_ = config.cameras;
  robot::forward_kinematics(*model_, *data_, Eigen::VectorXd::Zero(model_->num_dofs()));
  for (const std::string& c : names_) {
    try {
      render::camera_for(*model_, c, data_->link_poses);
    } catch (const InputError& e) {
      config_error(ctx, config, config.cameras, e.what());
    }
  }
}

std::vector<render::Camera> BelievedEyes::pose(const Eigen::VectorXd& encoders) {
  robot::forward_kinematics(*model_, *data_, encoders + offsets_);
  return {render::camera_for(*model_, names_[0], data_->link_poses),
          render::camera_for(*model_, names_[1], data_->link_poses)};
}

}  // namespace somasim::plugins
