#pragma once
// cartesian_velocity: moves a point fixed to any link of a chain at the velocity given on the
// `velocity` port (root frame), with the damped pseudo-inverse of that point's Jacobian over
// the chain's dofs, joint-limit and velocity-limit aware (control::CartesianVelocityController
// holds the logic; pps_controller reuses it). Velocity-mode commands on the chain dofs only.
#include <memory>

#include "somasim/control/cartesian_velocity.hpp"
#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::plugins {

class CartesianVelocity : public Plugin {
 public:
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
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
