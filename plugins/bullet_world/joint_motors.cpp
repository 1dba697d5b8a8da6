#include "joint_motors.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::bullet_world {

JointMotors::JointMotors(RobotMultiBody& robot, btMultiBodyDynamicsWorld& world,
                         const MotorGains& gains, double dt, const Eigen::VectorXd& hold,
                         JointServo servo, const Eigen::Vector3d& gravity)
    : robot_(robot), world_(world), gains_(gains), dt_(dt), gravity_(gravity) {
  const robot::RobotModel& m = robot.model();
  const int n = m.num_dofs();
  const bool computed_torque = servo == JointServo::kComputedTorque && robot.has_multibody();
  if (computed_torque) {
    std::vector<bool> locked(static_cast<std::size_t>(n));
    for (int d = 0; d < n; ++d) locked[static_cast<std::size_t>(d)] = robot.locked(d);
    std::vector<robot::Inertial> inertials =
        robot::physical_inertials(m, kFrameLinkMass, kMinPrincipalInertia, locked);
    // Kinematic groups are not in the multibody: their joints carry none of their mass.
    for (int i = 0; i < m.num_links(); ++i)
      for (const int up : m.supporting_dofs(i))
        if (robot.kinematic(up)) inertials[static_cast<std::size_t>(i)] = robot::Inertial{};
    dynamics_ = std::make_unique<robot::InverseDynamics>(m, std::move(inertials));
    data_ = std::make_unique<robot::RobotData>(m);
    q_ = qd_ = qdd_ = Eigen::VectorXd::Zero(n);
  }
  mode_.assign(n, JointCommandMode::kPosition);
  position_.assign(n, 0.0);
  velocity_.assign(n, 0.0);
  motors_.resize(n);
  for (int d = 0; d < n; ++d) {
    const int link = robot.dof_link(d);
    if (link < 0) {  // locked or kinematic: no motor
      mode_[d] = robot.locked(d) ? JointCommandMode::kNone : JointCommandMode::kPosition;
      position_[d] = hold[d];
      continue;
    }
    if (!computed_torque) {
      auto motor = std::make_unique<btMultiBodyJointMotor>(&robot.multibody(), link, 0.0,
                                                           gains_.max_torque * dt_);
      motor->setErp(1.0);
      world_.addMultiBodyConstraint(motor.get());
      motors_[d] = std::move(motor);
    }
    const double lo = m.lower_limits()[d], hi = m.upper_limits()[d];
    if (lo < hi) {
      auto limit =
          std::make_unique<btMultiBodyJointLimitConstraint>(&robot.multibody(), link, lo, hi);
      limits_.push_back({d, std::move(limit), false});
    }
    set_position(d, hold[d], 0.0);
  }
  update_limits();
}

void JointMotors::update_limits() {
  const robot::RobotModel& m = robot_.model();
  for (Limit& l : limits_) {
    const double q = robot_.position(l.dof);
    const double margin = kLimitMargin + 4.0 * std::abs(robot_.velocity(l.dof)) * dt_;
    const bool near = q - m.lower_limits()[l.dof] < margin || m.upper_limits()[l.dof] - q < margin;
    if (near == l.active) continue;
    if (near)
      world_.addMultiBodyConstraint(l.constraint.get());
    else
      world_.removeMultiBodyConstraint(l.constraint.get());
    l.active = near;
  }
}

void JointMotors::advance_kinematic(double max_speed) {
  const robot::RobotModel& m = robot_.model();
  const int n = m.num_dofs();
  Eigen::VectorXd q(n), dq = Eigen::VectorXd::Zero(n);
  const double max_step = max_speed * dt_;
  for (int d = 0; d < n; ++d) {
    const double now = robot_.position(d);
    q[d] = now;
    if (!robot_.kinematic(d)) {  // locked or dynamic: as it is
      dq[d] = robot_.velocity(d);
      continue;
    }
    const auto k = static_cast<std::size_t>(d);
    double target =
        mode_[k] == JointCommandMode::kVelocity ? now + velocity_[k] * dt_ : position_[k];
    target = std::clamp(target, m.lower_limits()[d], m.upper_limits()[d]);
    q[d] = now + std::clamp(target - now, -max_step, max_step);
    dq[d] = (q[d] - now) / dt_;
  }
  robot_.move_kinematic(q, dq);
}

void JointMotors::apply_torques() {
  if (!dynamics_) return;
  const robot::RobotModel& m = robot_.model();
  const double w = gains_.position_gain;
  for (int d = 0; d < m.num_dofs(); ++d) {
    q_[d] = robot_.position(d);
    qd_[d] = robot_.velocity(d);
    const auto k = static_cast<std::size_t>(d);
    if (robot_.dof_link(d) < 0)
      qdd_[d] = 0.0;
    else if (mode_[k] == JointCommandMode::kVelocity)
      qdd_[d] = 2.0 * w * (velocity_[k] - qd_[d]);
    else
      qdd_[d] = w * w * (position_[k] - q_[d]) + 2.0 * w * (velocity_[k] - qd_[d]);
  }
  robot::forward_kinematics(m, *data_, q_);
  const Eigen::VectorXd& tau = dynamics_->torques(*data_, qd_, qdd_, gravity_);
  for (int d = 0; d < m.num_dofs(); ++d)
    if (const int link = robot_.dof_link(d); link >= 0)
      robot_.multibody().addJointTorque(link,
                                        std::clamp(tau[d], -gains_.max_torque, gains_.max_torque));
}

JointMotors::~JointMotors() {
  for (auto& l : limits_)
    if (l.active) world_.removeMultiBodyConstraint(l.constraint.get());
  for (auto& m : motors_)
    if (m) world_.removeMultiBodyConstraint(m.get());
}

void JointMotors::set_position(int dof, double q, double v_feed_forward) {
  const robot::RobotModel& m = robot_.model();
  q = std::clamp(q, m.lower_limits()[dof], m.upper_limits()[dof]);
  mode_[dof] = JointCommandMode::kPosition;
  position_[dof] = q;
  velocity_[dof] = v_feed_forward;
  if (!motors_[dof]) return;
  // btMultiBodyJointMotor: v_target = kp·erp·(q* − q)/dt + v + kd·(v* − v), erp = 1.
  motors_[dof]->setPositionTarget(q, gains_.position_gain * dt_);
  motors_[dof]->setVelocityTarget(v_feed_forward, gains_.velocity_gain);
}

void JointMotors::set_velocity(int dof, double v) {
  mode_[dof] = JointCommandMode::kVelocity;
  position_[dof] = robot_.position(dof);
  velocity_[dof] = v;
  if (!motors_[dof]) return;
  motors_[dof]->setPositionTarget(0.0, 0.0);
  motors_[dof]->setVelocityTarget(v, gains_.velocity_gain);
}

void JointMotors::apply(const JointCommand& c, double t) {
  if (c.mode.empty()) return;
  const robot::RobotModel& m = robot_.model();
  const auto n = static_cast<std::size_t>(m.num_dofs());
  auto size_error = [&](const char* what, std::size_t got) {
    throw RunError(
        fmt::format("t = {:.3f} s: joint command: expected {} {}, got {}", t, n, what, got));
  };
  if (c.mode.size() != n) size_error("modes", c.mode.size());
  const bool any_position =
      std::find(c.mode.begin(), c.mode.end(), JointCommandMode::kPosition) != c.mode.end();
  const bool any_velocity =
      std::find(c.mode.begin(), c.mode.end(), JointCommandMode::kVelocity) != c.mode.end();
  if (any_position && static_cast<std::size_t>(c.position.size()) != n)
    size_error("position targets", c.position.size());
  const bool has_velocity = static_cast<std::size_t>(c.velocity.size()) == n;
  if (any_velocity && !has_velocity) size_error("velocity targets", c.velocity.size());
  for (std::size_t d = 0; d < n; ++d) {
    const int dof = static_cast<int>(d);
    auto not_finite = [&](const char* what, double v) {
      throw RunError(fmt::format("t = {:.3f} s: joint command for '{}': {} is {}", t,
                                 m.joint(m.dof_joint(dof)).name, what, v));
    };
    const double v = has_velocity ? c.velocity[dof] : 0.0;
    if (c.mode[d] != JointCommandMode::kNone && robot_.locked(dof))
      throw RunError(fmt::format(
          "t = {:.3f} s: joint command for '{}': the joint is locked (param locked_joints); "
          "send kNone for it",
          t, m.joint(m.dof_joint(dof)).name));
    switch (c.mode[d]) {
      case JointCommandMode::kNone:
        break;
      case JointCommandMode::kPosition:
        if (!std::isfinite(c.position[dof])) not_finite("the position target", c.position[dof]);
        if (!std::isfinite(v)) not_finite("the velocity feed-forward", v);
        set_position(dof, c.position[dof], v);
        break;
      case JointCommandMode::kVelocity:
        if (!std::isfinite(v)) not_finite("the velocity target", v);
        set_velocity(dof, v);
        break;
    }
  }
}

}  // namespace somasim::bullet_world
