#pragma once
// The `robot` parameter shared by the controllers: a robot description file, relative to the
// experiment file, loaded once per process (shared_robot_model).
#include <memory>

#include "somasim/plugin.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

void add_robot_param(PluginSpec& spec);
/// The model named by the `robot` parameter; bad files are reported against that parameter.
std::shared_ptr<const robot::RobotModel> load_robot_param(const NodeContext& ctx);
/// RunError unless the JointState has one position and one velocity per dof of the model.
void check_joint_state(const NodeContext& ctx, const robot::RobotModel& model,
                       const Eigen::VectorXd& position, const Eigen::VectorXd& velocity);

}  // namespace somasim::plugins
