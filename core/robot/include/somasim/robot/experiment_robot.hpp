#pragma once
/// @file
/// The robots of an experiment, as plugins reach them. An experiment declares its robots once
/// (`robots: {icub: ../assets/robots/icub_v1.yaml}`); a plugin names one in its `robot`
/// parameter (empty: the experiment's only robot). Each robot is loaded once per run and the
/// same immutable model is shared by every node of that run (the world, the skin, the
/// controllers see one model); nothing outlives the run.
#include <memory>
#include <string>

#include "somasim/plugin.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// What the `robot` parameter means (its documentation).
inline constexpr const char* kRobotParamDoc =
    "the robot: a name from the experiment's 'robots:' section (empty: its only robot)";

/// The `robot` parameter as a config block (somasim/config.hpp): `v.block(robot)` declares it,
/// experiment_robot(ctx, config.robot) loads the model it names.
struct RobotParam {
  static constexpr const char* kKey = "robot";  ///< the parameter's name
  std::string name;                             ///< "" picks the experiment's only robot
  template <class V>
  void visit(V& v) {
    v.field(kKey, name).doc(kRobotParamDoc);
  }
};

/// Declares the string parameter `name` (default "robot") that names the robot a plugin uses.
ParamSpec& add_robot_param(PluginSpec& spec, const std::string& name = "robot");

/// The model of the robot named by the node's parameter `param`. InputError when the name is
/// not in the experiment's `robots:` section (located at the parameter) or when the file does
/// not load (located at the `robots:` entry, with the loader's message).
std::shared_ptr<const RobotModel> experiment_robot(NodeContext& ctx,
                                                   const std::string& param = RobotParam::kKey);
/// The model of the robot a config's RobotParam block names (errors as above).
inline std::shared_ptr<const RobotModel> experiment_robot(NodeContext& ctx,
                                                          const RobotParam& /*block*/) {
  return experiment_robot(ctx, RobotParam::kKey);
}

/// Throws InputError located at the `robots:` entry of the robot named by `param`, naming the
/// robot and the node: for problems of the robot's files found by a plugin (e.g. a mesh that
/// the physics or the renderer cannot use).
[[noreturn]] void robot_error(NodeContext& ctx, const std::string& message,
                              const std::string& param = RobotParam::kKey);

/// RunError unless a joint state has one position and one velocity per dof of `model` and
/// finite positions (for plugins that read a JointState input).
void check_joint_state(const NodeContext& ctx, const RobotModel& model,
                       const Eigen::VectorXd& position, const Eigen::VectorXd& velocity);

}  // namespace somasim::robot
