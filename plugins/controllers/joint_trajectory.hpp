#pragma once
// joint_trajectory: joint-space trajectories (linear or minimum-jerk) through waypoints given in
// the YAML, or to targets arriving on the optional `target` port.
//
// Waypoints: `joints` names the controlled joints (space-separated), `targets_deg` holds one
// row of targets per waypoint (waypoint-major: the first len(joints) values are waypoint 0),
// `durations` the time to reach each waypoint from the previous one. The trajectory starts from
// the measured joint state at the node's first step (with a non-empty state). A target on the
// port (new `id`) replaces what remains: a single segment from the current reference to the
// target over its duration, on the target's active dofs plus the joints already controlled.
//
// Output: position-mode commands with the profile's velocity as feed-forward on the controlled
// joints (kNone elsewhere), holding the last waypoint once reached; `done` is 1 when the last
// waypoint (or target) is reached — by time, and within `done_tolerance_deg` of the measured
// positions when that is > 0 — and when nothing was asked.
#include <memory>
#include <vector>

#include "somasim/config.hpp"
#include "somasim/control/joint_target.hpp"
#include "somasim/control/trajectory.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class JointTrajectoryController : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> joints;
    std::vector<double> targets_deg;  // [deg], prismatic joints [m]
    std::vector<double> durations;    // [s]
    control::Profile profile = control::Profile::kMinimumJerk;
    double done_tolerance_deg = 0.0;  // [deg]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<JointState> state;
    OptionalIn<JointTarget> target;
    Out<JointCommand> command;
    Out<double> done;
    template <class V>
    void visit(V& v);
  };

  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  void read_waypoints(const NodeContext& ctx);
  void start_target(double t, const JointState& state);
  void write_command(double t, const JointState& state);

  std::shared_ptr<const robot::RobotModel> model_;
  double tolerance_ = 0.0;                                     // [rad]
  std::vector<int> joint_dofs_;                                // from `joints`
  std::vector<control::JointTrajectory::Waypoint> waypoints_;  // in joint_dofs_ order
  Config config_;
  Ports ports_;
  // state
  bool started_ = false;
  std::uint64_t last_target_id_ = 0;
  std::vector<int> active_dofs_;  // dofs of trajectory_
  control::JointTrajectory trajectory_;
  Eigen::VectorXd reference_, reference_velocity_;
  int targets_received_ = 0;
};

}  // namespace somasim::plugins
