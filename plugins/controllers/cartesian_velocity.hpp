#pragma once
// cartesian_velocity: moves a point fixed to any link of a chain at the velocity given on the
// `velocity` port (root frame), with the damped pseudo-inverse of that point's Jacobian over
// the chain's dofs, joint-limit and velocity-limit aware (control::CartesianVelocityController
// holds the logic; pps_controller reuses it). Velocity-mode commands on the chain dofs only.
#include <memory>

#include "somasim/config.hpp"
#include "somasim/control/cartesian_velocity.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::plugins {

class CartesianVelocity : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string chain;
    std::string base;
    std::string tip;
    std::string link;
    std::vector<double> point{0, 0, 0};                // [m]
    double damping = 0.02;                             // [m]
    double singular_threshold = 0.04;                  // [m]
    std::vector<double> max_joint_velocity_deg{60.0};  // [deg/s]
    double limit_margin_deg = 2.0;                     // [deg]
    bool hold_orientation = false;
    double orientation_gain = 2.0;  // [1/s]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<JointState> state;
    In<Eigen::Vector3d> velocity;
    Out<JointCommand> command;
    Out<Eigen::Vector3d> point;
    Out<Eigen::Vector3d> point_velocity;
    Out<double> limited;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  std::unique_ptr<control::CartesianVelocityController> controller_;
  const JointState* state_ = nullptr;
  const Eigen::Vector3d* velocity_ = nullptr;
  JointCommand* command_ = nullptr;
  Eigen::Vector3d* point_ = nullptr;
  Eigen::Vector3d* point_velocity_ = nullptr;
  double* limited_ = nullptr;
  long steps_ = 0, limited_steps_ = 0;
};

}  // namespace somasim::plugins
