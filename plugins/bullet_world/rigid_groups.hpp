#pragma once
/// @file
/// Which model links move together. A link joined to its parent by a fixed joint, or by a joint
/// locked at its initial value (param `locked_joints`), belongs to its parent's rigid group; each
/// group becomes one Bullet body (one multibody link per unlocked dof, plus the base), whose
/// collision compound holds the geometry of all its links. A group is named by its root link, the
/// "representative" (the model root or the child link of an unlocked movable joint).
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::bullet_world {

struct RigidGroups {
  /// `locked`: per dof (empty = none locked); `q`: joint values the locked joints keep (model dof
  /// order) [rad]/[m].
  RigidGroups(const robot::RobotModel& model, const std::vector<bool>& locked,
              const Eigen::VectorXd& q);

  /// Representative link of each model link's group.
  std::vector<int> rep;
  /// Each model link's frame in its representative's frame (constant).
  std::vector<Eigen::Isometry3d> in_rep;
  /// Representatives in model (topological) order; representatives()[0] is the root.
  std::vector<int> representatives;
  /// Body index (position in `representatives`) of each representative link, -1 for others.
  std::vector<int> body_of_rep;
};

/// A joint-list parameter (`locked_joints`, `kinematic_joints`): joint names, or `all`
/// (every dof). Returns a per-dof mask. InputError for unknown or fixed joints (with a
/// suggestion), to be prefixed by the parameter's location.
std::vector<bool> parse_joint_set(const std::vector<std::string>& names,
                                  const robot::RobotModel& model);

/// The dofs that move kinematically: every dof not locked under `all_kinematic`, else the
/// `kinematic` mask. InputError (to be prefixed by the `kinematic_joints` location) when a joint
/// is both locked and kinematic, or when a dynamic joint moves below a kinematic one (a
/// kinematic group carries only kinematic or locked joints: it is posed by forward kinematics
/// and cannot carry a dynamic subtree).
std::vector<bool> kinematic_dofs(const robot::RobotModel& model, const std::vector<bool>& locked,
                                 bool all_kinematic, const std::vector<bool>& kinematic);

}  // namespace somasim::bullet_world
