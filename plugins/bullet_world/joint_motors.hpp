#pragma once
/// @file
/// Joint motors and limits of the robot multibody.
///
/// Each dof has a Bullet btMultiBodyJointMotor: an implicit velocity constraint solved with the
/// contacts, bounded by max_torque · dt per step. Its target velocity is
///   v_target = position_gain · (q* − q) + v*        (velocity_gain = 1)
/// (in general position_gain·(q* − q) + v + velocity_gain·(v* − v)), so a position step decays
/// like exp(−position_gain · t) while the torque bound is not reached: with the default
/// position_gain = 40 /s the error falls below 2 % after 4/40 = 0.1 s (the documented settling
/// time is 0.15 s, which also covers the saturated start of large steps; see bullet_world.hpp).
/// Position targets are clamped into the joint limits; the limits themselves are Bullet
/// btMultiBodyJointLimitConstraints.
#include <memory>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>

#include "robot_multibody.hpp"
#include "somasim/robot_ports.hpp"

namespace somasim::bullet_world {

struct MotorGains {
  double position_gain = 40.0;  ///< [1/s]
  double velocity_gain = 1.0;   ///< [-], 0..1
  double max_torque = 20.0;     ///< [N·m] (prismatic joints: [N])
};

class JointMotors {
 public:
  /// Motors start by holding `hold` (model dof order).
  JointMotors(RobotMultiBody& robot, btMultiBodyDynamicsWorld& world, const MotorGains& gains,
              double dt, const Eigen::VectorXd& hold);
  ~JointMotors();
  JointMotors(const JointMotors&) = delete;
  JointMotors& operator=(const JointMotors&) = delete;

  /// Applies a command. Dofs with mode kNone keep their previous target; an empty command (no
  /// modes yet) changes nothing. RunError (naming `t` [s] and the joint) for non-finite values
  /// or vectors of the wrong size.
  void apply(const JointCommand& command, double t);

  JointCommandMode mode(int dof) const { return mode_[dof]; }
  double position_target(int dof) const { return position_[dof]; }

 private:
  void set_position(int dof, double q, double v_feed_forward);
  void set_velocity(int dof, double v);

  const RobotMultiBody& robot_;
  btMultiBodyDynamicsWorld& world_;
  MotorGains gains_;
  double dt_;
  std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors_;
  std::vector<std::unique_ptr<btMultiBodyJointLimitConstraint>> limits_;
  std::vector<JointCommandMode> mode_;
  std::vector<double> position_;
};

}  // namespace somasim::bullet_world
