#include "somasim/robot/joint_text.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/units.hpp"

namespace somasim::robot {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\n") - b + 1);
}

bool is_revolute(const RobotModel& model, int dof) {
  return model.joint(model.dof_joint(dof)).type == JointType::Revolute;
}

/// Calls `use(dof, value, text of the value)` for every "joint: value" entry of `text`, value in
/// the dof's unit ([rad] / [m]); InputError for malformed entries, unknown or repeated joints.
void for_each_joint_value(const RobotModel& model, const std::string& text,
                          const std::function<void(int, double, const std::string&)>& use) {
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
    const int dof = static_cast<int>(it - joints.begin());
    const bool revolute = is_revolute(model, dof);
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
    if (given[static_cast<std::size_t>(dof)])
      throw InputError("joint '" + name + "' is given twice");
    given[static_cast<std::size_t>(dof)] = true;
    use(dof, revolute ? deg_to_rad(v) : v, value);
  }
}

}  // namespace

Eigen::VectorXd parse_joint_offsets(const RobotModel& model, const std::string& text) {
  Eigen::VectorXd offsets = Eigen::VectorXd::Zero(model.num_dofs());
  for_each_joint_value(model, text,
                       [&](int dof, double v, const std::string&) { offsets[dof] = v; });
  return offsets;
}

Eigen::VectorXd parse_posture_deg(const RobotModel& model, const std::string& text) {
  const int n = model.num_dofs();
  Eigen::VectorXd q(n);
  for (int d = 0; d < n; ++d)
    q[d] = std::clamp(0.0, model.lower_limits()[d], model.upper_limits()[d]);
  for_each_joint_value(model, text, [&](int dof, double v, const std::string& value) {
    const double lo = model.lower_limits()[dof], hi = model.upper_limits()[dof];
    if (v < lo - 1e-9 || v > hi + 1e-9) {
      const bool revolute = is_revolute(model, dof);
      const double scale = revolute ? kRadPerDeg : 1.0;
      throw InputError(fmt::format("joint '{}': {} {} is outside the limits [{:g}, {:g}]",
                                   model.joint(model.dof_joint(dof)).name, value,
                                   revolute ? "deg" : "m", lo / scale, hi / scale));
    }
    q[dof] = std::clamp(v, lo, hi);
  });
  return q;
}

}  // namespace somasim::robot
