#pragma once
/// @file
/// Detects a physics blow-up after a step: non-finite or runaway joint/object velocities, or an
/// interpenetration deeper than a bound. Throws RunError naming the sim-time and the body.
#include "contact_extraction.hpp"
#include "object_manager.hpp"
#include "robot_multibody.hpp"

namespace somasim::bullet_world {

struct BlowupLimits {
  double max_joint_speed = 99.0;   ///< [rad/s] (prismatic: [m/s]); < Bullet's 100 clamp
  double max_object_speed = 50.0;  ///< [m/s]
  double max_penetration = 0.02;   ///< [m]
};

/// `t` [s]: the sim-time the state belongs to.
void check_blowup(const RobotMultiBody& robot, const ObjectManager& objects,
                  const Penetration& deepest, const BlowupLimits& limits, double t);

}  // namespace somasim::bullet_world
