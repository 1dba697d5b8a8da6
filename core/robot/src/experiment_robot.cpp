#include "somasim/robot/experiment_robot.hpp"

#include "somasim/experiment.hpp"
#include "somasim/robot/robot_loader.hpp"

namespace somasim::robot {

ParamSpec& add_robot_param(PluginSpec& spec, const std::string& name) {
  return spec.add_string(name).defaults(std::string()).describe(kRobotParamDoc);
}

std::shared_ptr<const RobotModel> experiment_robot(NodeContext& ctx, const std::string& param) {
  const RobotSpec& spec = ctx.robot_spec(param);
  return ctx.run_shared<RobotModel>("robot:" + spec.name, [&spec] {
    try {
      return std::make_shared<const RobotModel>(load_robot_model(spec.file));
    } catch (const InputError& e) {
      throw InputError(spec.where.str() + ": robot '" + spec.name + "': " + e.what());
    }
  });
}

void robot_error(NodeContext& ctx, const std::string& message, const std::string& param) {
  const RobotSpec& spec = ctx.robot_spec(param);
  throw InputError(spec.where.str() + ": robot '" + spec.name + "' (used by node '" +
                   ctx.node_name() + "'): " + message);
}

void check_joint_state(const NodeContext& ctx, const RobotModel& model,
                       const Eigen::VectorXd& position, const Eigen::VectorXd& velocity) {
  const auto n = model.num_dofs();
  if (position.size() != n || velocity.size() != n)
    throw RunError(ctx.node_name() + ": joint state has " + std::to_string(position.size()) +
                   " positions and " + std::to_string(velocity.size()) + " velocities, expected " +
                   std::to_string(n) + " (the dofs of robot '" + model.name() + "')");
  if (!position.allFinite())
    throw RunError(ctx.node_name() + ": joint state holds non-finite positions");
}

}  // namespace somasim::robot
