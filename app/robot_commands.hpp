#pragma once
// `somasim robot ...`: tools on robot descriptions.
#include <string>

namespace somasim::app {

/// `somasim robot export-urdf ROBOT [--out FILE.urdf] [--overlay FILE.yaml]`: the robot (YAML
/// or URDF) as a URDF, to FILE or stdout; with --overlay, also the YAML overlay that extends the
/// written URDF with the frames, cameras and skin patches URDF cannot hold. Exit 0, or 2 (bad
/// input: the robot, or a file that cannot be written).
int cmd_robot_export_urdf(const std::string& robot, const std::string& out,
                          const std::string& overlay);

}  // namespace somasim::app
