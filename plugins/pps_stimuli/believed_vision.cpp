#include "believed_vision.hpp"

#include <string>

#include "somasim/error.hpp"

namespace somasim::plugins {

BelievedVision::BelievedVision(std::shared_ptr<const robot::RobotModel> model, int vision_link)
    : model_(std::move(model)), link_(vision_link), true_(*model_), believed_(*model_) {}

const Eigen::Isometry3d& BelievedVision::update(const Eigen::VectorXd& q_true,
                                                const Eigen::VectorXd& q_believed) {
  const auto n = model_->num_dofs();
  for (const auto& [q, input] : {std::pair<const Eigen::VectorXd*, const char*>{&q_true, "state"},
                                 {&q_believed, "believed_state"}})
    if (q->size() != n)
      throw RunError(std::string("input '") + input + "': expected " + std::to_string(n) +
                     " joint values (robot '" + model_->name() + "'), got " +
                     std::to_string(q->size()));
  robot::forward_kinematics(*model_, true_, q_true);
  robot::forward_kinematics(*model_, believed_, q_believed);
  transform_ = robot::link_pose(believed_, link_) * robot::link_pose(true_, link_).inverse();
  return transform_;
}

}  // namespace somasim::plugins
