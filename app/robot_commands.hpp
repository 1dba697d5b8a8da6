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

/// Options of `somasim robot export-mjcf`.
struct MjcfExportArgs {
  std::string posture;            ///< joint text [deg] the servo gains are tuned at ("" = all 0)
  double servo_bandwidth = 40.0;  ///< [1/s]
  double max_torque = 20.0;       ///< [N·m]
  bool servos = true;
};

/// `somasim robot export-mjcf ROBOT [--out FILE.xml] [--posture TEXT] [--servo-bandwidth W]
/// [--max-torque T] [--no-servos]`: the robot as a MuJoCo model (robot/mjcf_export.hpp), to FILE
/// or stdout. Exit 0, or 2 (bad input: the robot, the posture, or a file that cannot be written).
int cmd_robot_export_mjcf(const std::string& robot, const std::string& out,
                          const MjcfExportArgs& args);

}  // namespace somasim::app
