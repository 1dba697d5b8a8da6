#include "somasim/robot/joint_offsets.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::robot {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\n") - b + 1);
}

}  // namespace

Eigen::VectorXd parse_joint_offsets(const RobotModel& model, const std::string& text) {
  Eigen::VectorXd offsets = Eigen::VectorXd::Zero(model.num_dofs());
  std::vector<std::string> joints;
  for (int d = 0; d < model.num_dofs(); ++d) joints.push_back(model.joint(model.dof_joint(d)).name);
  std::vector<bool> given(joints.size(), false);
  std::istringstream entries(text);
  for (std::string entry; std::getline(entries, entry, ',');) {
    entry = trim(entry);
    if (entry.empty()) continue;
    const auto colon = entry.find(':');
    if (colon == std::string::npos)
      throw InputError("expected 'joint: value', got '" + entry + "' (entries separated by ',')");
    const std::string name = trim(entry.substr(0, colon));
    const std::string value = trim(entry.substr(colon + 1));
    const auto it = std::find(joints.begin(), joints.end(), name);
    if (it == joints.end())
      throw InputError("unknown joint '" + name + "'" + did_you_mean(name, joints) +
                       " (movable joints of the robot)");
    const auto dof = static_cast<std::size_t>(it - joints.begin());
    const bool revolute =
        model.joint(model.dof_joint(static_cast<int>(dof))).type == JointType::Revolute;
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != value.size() || !std::isfinite(v))
      throw InputError("joint '" + name + "': expected a number " + (revolute ? "[deg]" : "[m]") +
                       ", got '" + value + "'");
    if (given[dof]) throw InputError("joint '" + name + "' is given twice");
    given[dof] = true;
    offsets[static_cast<Eigen::Index>(dof)] = revolute ? v * M_PI / 180.0 : v;
  }
  return offsets;
}

}  // namespace somasim::robot
