#include "rigid_groups.hpp"

#include <sstream>

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

std::vector<bool> parse_locked_joints(const std::vector<std::string>& names,
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

}  // namespace somasim::bullet_world
