#include "somasim/control/joint_command_merge.hpp"

namespace somasim::control {

std::string merge_joint_commands(const std::vector<const JointCommand*>& inputs,
                                 MergeConflict conflict, JointCommand& out,
                                 const std::vector<std::string>& names) {
  const auto name = [&](std::size_t i) {
    return i < names.size() ? "'" + names[i] + "'" : "input " + std::to_string(i);
  };
  std::size_t dofs = 0, first = 0;
  bool sized = false;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const JointCommand* c = inputs[i];
    if (!c || c->mode.empty()) continue;
    const std::size_t n = c->mode.size();
    if (static_cast<std::size_t>(c->position.size()) != n ||
        static_cast<std::size_t>(c->velocity.size()) != n)
      return name(i) + " is malformed: " + std::to_string(n) + " modes, " +
             std::to_string(c->position.size()) + " positions and " +
             std::to_string(c->velocity.size()) + " velocities";
    if (!sized) {
      dofs = n;
      first = i;
      sized = true;
    } else if (n != dofs) {
      return name(i) + " has " + std::to_string(n) + " dofs, expected " + std::to_string(dofs) +
             " (as " + name(first) + ")";
    }
  }
  if (out.mode.size() != dofs) {
    out.position.setZero(static_cast<Eigen::Index>(dofs));
    out.velocity.setZero(static_cast<Eigen::Index>(dofs));
  }
  out.mode.assign(dofs, JointCommandMode::kNone);
  std::vector<int> owner(dofs, -1);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const JointCommand* c = inputs[i];
    if (!c || c->mode.empty()) continue;
    for (std::size_t d = 0; d < dofs; ++d) {
      if (c->mode[d] == JointCommandMode::kNone) continue;
      if (owner[d] >= 0 && conflict == MergeConflict::kError)
        return name(static_cast<std::size_t>(owner[d])) + " and " + name(i) + " both command dof " +
               std::to_string(d);
      owner[d] = static_cast<int>(i);
      out.mode[d] = c->mode[d];
      out.position[static_cast<Eigen::Index>(d)] = c->position[static_cast<Eigen::Index>(d)];
      out.velocity[static_cast<Eigen::Index>(d)] = c->velocity[static_cast<Eigen::Index>(d)];
    }
  }
  return "";
}

}  // namespace somasim::control
