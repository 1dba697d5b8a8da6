#include "somasim/control/posture_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::control {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\n") - b + 1);
}

}  // namespace

Eigen::VectorXd parse_posture_deg(const std::string& text, const robot::RobotModel& model) {
  const int n = model.num_dofs();
  Eigen::VectorXd q(n);
  for (int d = 0; d < n; ++d)
    q[d] = std::clamp(0.0, model.lower_limits()[d], model.upper_limits()[d]);
  std::vector<std::string> dof_names;
  for (int d = 0; d < n; ++d) dof_names.push_back(model.joint(model.dof_joint(d)).name);

  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    const std::string pair = trim(text.substr(start, end - start));
    start = end + 1;
    if (pair.empty()) continue;
    const auto colon = pair.find(':');
    const std::string name = trim(pair.substr(0, colon));
    const std::string value = colon == std::string::npos ? "" : trim(pair.substr(colon + 1));
    char* parse_end = nullptr;
    const double v = std::strtod(value.c_str(), &parse_end);
    if (colon == std::string::npos || value.empty() || *parse_end != '\0' || !std::isfinite(v))
      throw InputError("expected 'joint: value' pairs separated by commas, got '" + pair + "'");
    const auto it = std::find(dof_names.begin(), dof_names.end(), name);
    if (it == dof_names.end())
      throw InputError("unknown joint '" + name + "'" + did_you_mean(name, dof_names));
    const int d = static_cast<int>(it - dof_names.begin());
    const bool revolute = model.joint(model.dof_joint(d)).type == robot::JointType::Revolute;
    const double scale = revolute ? M_PI / 180.0 : 1.0;
    const double lo = model.lower_limits()[d], hi = model.upper_limits()[d];
    if (v * scale < lo - 1e-9 || v * scale > hi + 1e-9)
      throw InputError(fmt::format("joint '{}': {} {} is outside the limits [{:g}, {:g}]", name,
                                   value, revolute ? "deg" : "m", lo / scale, hi / scale));
    q[d] = std::clamp(v * scale, lo, hi);
  }
  return q;
}

}  // namespace somasim::control
