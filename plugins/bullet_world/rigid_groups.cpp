#include "rigid_groups.hpp"

#include <sstream>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::bullet_world {

RigidGroups::RigidGroups(const robot::RobotModel& model, const std::vector<bool>& locked,
                         const Eigen::VectorXd& q) {
  const int n = model.num_links();
  robot::RobotData data(model);
  robot::forward_kinematics(model, data, q);
  rep.resize(n);
  in_rep.resize(n);
  body_of_rep.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    const robot::Link& link = model.link(i);
    bool rigid = false;
    if (link.parent_joint >= 0) {
      const robot::Joint& j = model.joint(link.parent_joint);
      rigid = j.dof < 0 || (!locked.empty() && locked[j.dof]);
    }
    // Parents come first (topological order), so rep[parent] is known.
    rep[i] = rigid ? rep[link.parent_link] : i;
    if (rep[i] == i) {
      body_of_rep[i] = static_cast<int>(representatives.size());
      representatives.push_back(i);
      in_rep[i] = Eigen::Isometry3d::Identity();
    } else {
      in_rep[i] = data.link_poses[rep[i]].inverse() * data.link_poses[i];
    }
  }
}

std::vector<bool> parse_joint_set(const std::vector<std::string>& names,
                                  const robot::RobotModel& model) {
  std::vector<bool> locked(model.num_dofs(), false);
  for (const std::string& name : names) {
    if (name == "all")
      locked.assign(model.num_dofs(), true);
    else
      locked[model.dof_index(name)] = true;
  }
  return locked;
}

std::vector<bool> kinematic_dofs(const robot::RobotModel& model, const std::vector<bool>& locked,
                                 bool all_kinematic, const std::vector<bool>& kinematic) {
  const auto n = static_cast<std::size_t>(model.num_dofs());
  std::vector<bool> moved(n, false);
  for (std::size_t d = 0; d < n; ++d) {
    const bool is_locked = d < locked.size() && locked[d];
    const bool listed = d < kinematic.size() && kinematic[d];
    if (listed && is_locked)
      throw InputError(
          fmt::format("joint '{}' is both locked and kinematic (also in locked_joints)",
                      model.joint(model.dof_joint(static_cast<int>(d))).name));
    moved[d] = !is_locked && (all_kinematic || listed);
  }
  for (std::size_t d = 0; d < n; ++d) {
    const bool is_locked = d < locked.size() && locked[d];
    if (moved[d] || is_locked) continue;
    const robot::Joint& j = model.joint(model.dof_joint(static_cast<int>(d)));
    for (const int up : model.supporting_dofs(j.child_link))
      if (moved[static_cast<std::size_t>(up)])
        throw InputError(fmt::format(
            "joint '{}' is kinematic but '{}' below it is dynamic: a kinematic group carries only "
            "kinematic or locked joints (add '{}' to kinematic_joints or locked_joints)",
            model.joint(model.dof_joint(up)).name, j.name, j.name));
  }
  return moved;
}

}  // namespace somasim::bullet_world
