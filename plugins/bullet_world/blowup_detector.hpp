#pragma once
/// @file
/// Detects a physics blow-up after a step: non-finite or runaway joint/object velocities, or an
/// interpenetration deeper than a bound. Throws RunError naming the sim-time, the body and the
/// pairs of bodies in contact at that step (what drove it, as far as the contacts tell).
#include <string>

#include "contact_extraction.hpp"
#include "object_manager.hpp"
#include "robot_multibody.hpp"

namespace somasim::bullet_world {

struct BlowupLimits {
  double max_joint_speed = 99.0;   ///< [rad/s] (prismatic: [m/s]); < Bullet's 100 clamp
  double max_object_speed = 50.0;  ///< [m/s]
  double max_penetration = 0.02;   ///< [m]
};

/// `t` [s]: the sim-time the state belongs to; `contacts`: the contact points of that step.
void check_blowup(const RobotMultiBody& robot, const ObjectManager& objects,
                  const Contacts& contacts, const Penetration& deepest, const BlowupLimits& limits,
                  double t);

/// "bodies in contact: link 'a' - object 'b' (1.2 N), ..." (each pair once, at most
/// `max_pairs`, with its largest normal force), or "no bodies in contact".
std::string contact_pairs_text(const robot::RobotModel& model, const ObjectManager& objects,
                               const Contacts& contacts, std::size_t max_pairs = 8);

}  // namespace somasim::bullet_world
