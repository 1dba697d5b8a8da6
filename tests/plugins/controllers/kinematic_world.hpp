#pragma once
// A stand-in for the physics world in controller tests: perfect joint servos. Position-mode
// joints jump to their target, velocity-mode joints integrate their velocity (explicit Euler),
// kNone joints stay. No clamping at the limits, so tests see what the controller asked for.
#include <memory>
#include <string>

#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::testing {

inline std::string icub_path() {
  return std::string(SOMASIM_SOURCE_DIR) + "/assets/robots/icub_v1.yaml";
}

struct KinematicWorld {
  explicit KinematicWorld(double dt_s)
      : model(robot::load_robot_model_shared(icub_path())), dt(dt_s) {
    // Mid-range start so every joint is within its limits.
    state.position = 0.5 * (model->lower_limits() + model->upper_limits());
    state.velocity.setZero(model->num_dofs());
  }
  int dof(const std::string& joint) const { return model->dof_index(joint); }

  void apply(const JointCommand& c) {
    if (c.mode.empty()) return;
    state.velocity.setZero();
    for (int d = 0; d < model->num_dofs(); ++d) {
      switch (c.mode[static_cast<std::size_t>(d)]) {
        case JointCommandMode::kPosition:
          state.velocity[d] = (c.position[d] - state.position[d]) / dt;
          state.position[d] = c.position[d];
          break;
        case JointCommandMode::kVelocity:
          state.velocity[d] = c.velocity[d];
          state.position[d] += c.velocity[d] * dt;
          break;
        case JointCommandMode::kNone:
          break;
      }
    }
  }

  std::shared_ptr<const robot::RobotModel> model;
  double dt;
  JointState state;
};

}  // namespace somasim::testing
