#include "robot_param.hpp"

#include "somasim/robot/robot_cache.hpp"

namespace somasim::plugins {

void add_robot_param(PluginSpec& spec) {
  spec.add_string("robot").describe(
      "robot description file (relative to the experiment file), e.g. "
      "../assets/robots/icub_v1.yaml; the same file as the world's");
}

std::shared_ptr<const robot::RobotModel> load_robot_param(const NodeContext& ctx) {
  try {
    return robot::shared_robot_model(ctx.resolve_input_path(ctx.param<std::string>("robot")));
  } catch (const InputError& e) {
    ctx.param_error("robot", e.what());
  }
}

void check_joint_state(const NodeContext& ctx, const robot::RobotModel& model,
                       const Eigen::VectorXd& position, const Eigen::VectorXd& velocity) {
  const auto n = model.num_dofs();
  if (position.size() != n || velocity.size() != n)
    throw RunError(ctx.node_name() + ": joint state has " + std::to_string(position.size()) +
                   " positions and " + std::to_string(velocity.size()) + " velocities, expected " +
                   std::to_string(n) + " (the dofs of robot '" + model.name() + "')");
  if (!position.allFinite())
    throw RunError(ctx.node_name() + ": joint state holds non-finite positions");
}

}  // namespace somasim::plugins
