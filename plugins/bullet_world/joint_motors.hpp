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
/// btMultiBodyJointLimitConstraints, in the world only while their joint is near a limit (within
/// kLimitMargin + 4·|v|·dt): far from it their (speculative) rows apply no impulse and would only
/// cost solver time.
///
/// Locked joints (`locked_joints`, folded into rigid bodies) have no motor: any command on them
/// other than kNone is a RunError naming the joint, so that a controller believing it moves a
/// locked joint fails loudly instead of silently doing nothing.
///
/// `JointServo::kComputedTorque` replaces the motor constraints by joint torques computed before
/// each step from the robot's own inverse dynamics (robot::InverseDynamics, the same masses as
/// the multibody): τ = M(q)·a + C(q, q̇)·q̇ + G(q) for the desired acceleration
///   a = ω²·(q* − q) + 2ω·(v* − q̇)   (position commands; velocity commands: a = 2ω·(v* − q̇)),
/// ω = position_gain, clamped to ±max_torque. Each joint then tracks like a critically damped
/// unit mass whatever the rest of the arm does; the solver is left with contacts and limits only,
/// so a step costs a fraction of the constraint motors' (what Bullet's multibody and the model
/// differ in, and what objects push, are disturbances the feedback rejects).
///
/// Kinematic joints (`joint_motion: kinematic`, `kinematic_joints`) have no motors either:
/// advance_kinematic() moves each to its target in one step — the position target (clamped into
/// the limits), or the position reached at the commanded velocity — at most `max_speed` · dt
/// per step, so that a step command cannot teleport the arm through what it touches. The
/// computed torques of the dynamic joints leave out the kinematic groups' masses (they are not
/// part of the multibody).
#include <memory>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>

#include "robot_multibody.hpp"
#include "somasim/name_table.hpp"
#include "somasim/robot/dynamics.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::bullet_world {

/// Distance to a joint limit [rad] (prismatic: [m]) below which its constraint is active.
inline constexpr double kLimitMargin = 0.05;

struct MotorGains {
  double position_gain = 40.0;  ///< [1/s]
  double velocity_gain = 1.0;   ///< [-], 0..1
  double max_torque = 20.0;     ///< [N·m] (prismatic joints: [N])
};

/// How the joints of a dynamic robot are driven to their commands.
enum class JointServo : std::uint8_t {
  kConstraint,      ///< Bullet motor constraints solved with the contacts (the default)
  kComputedTorque,  ///< joint torques from inverse dynamics, applied before each step
};
inline constexpr NamedValue<JointServo> kJointServoNames[] = {
    {JointServo::kConstraint, "constraint"}, {JointServo::kComputedTorque, "computed_torque"}};
constexpr std::span<const NamedValue<JointServo>> name_table(JointServo) {
  return kJointServoNames;
}

class JointMotors {
 public:
  /// Motors start by holding `hold` (model dof order). `gravity` [m/s², root frame] is what
  /// computed torques compensate.
  JointMotors(RobotMultiBody& robot, btMultiBodyDynamicsWorld& world, const MotorGains& gains,
              double dt, const Eigen::VectorXd& hold, JointServo servo = JointServo::kConstraint,
              const Eigen::Vector3d& gravity = Eigen::Vector3d::Zero());
  ~JointMotors();
  JointMotors(const JointMotors&) = delete;
  JointMotors& operator=(const JointMotors&) = delete;

  /// Adds the limit constraints of joints near a limit to the world and removes the others;
  /// call before each step.
  void update_limits();

  /// Applies a command. Dofs with mode kNone keep their previous target; an empty command (no
  /// modes yet) changes nothing. RunError (naming `t` [s] and the joint) for non-finite values
  /// or vectors of the wrong size, and for commands on locked joints.
  void apply(const JointCommand& command, double t);

  /// Kinematic joints: moves them towards their targets for a step of dt (see the file
  /// comment), at most `max_speed` [rad/s] ([m/s]); call after apply(), before the step.
  void advance_kinematic(double max_speed);

  /// Computed-torque servo: applies this step's joint torques to the multibody (see the file
  /// comment); call after apply() and update_limits(), before the step. No-op otherwise.
  void apply_torques();
  JointCommandMode mode(int dof) const { return mode_[dof]; }
  double position_target(int dof) const { return position_[dof]; }

 private:
  void set_position(int dof, double q, double v_feed_forward);
  void set_velocity(int dof, double v);

  RobotMultiBody& robot_;
  btMultiBodyDynamicsWorld& world_;
  MotorGains gains_;
  double dt_;
  std::vector<std::unique_ptr<btMultiBodyJointMotor>> motors_;
  struct Limit {
    int dof = -1;
    std::unique_ptr<btMultiBodyJointLimitConstraint> constraint;
    bool active = false;  ///< in the world
  };
  std::vector<Limit> limits_;
  std::vector<JointCommandMode> mode_;
  std::vector<double> position_;
  std::vector<double> velocity_;  ///< velocity targets or feed-forward [rad/s]
  // Computed-torque servo (null otherwise).
  std::unique_ptr<robot::InverseDynamics> dynamics_;
  std::unique_ptr<robot::RobotData> data_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
  Eigen::VectorXd q_, qd_, qdd_;
};

}  // namespace somasim::bullet_world
