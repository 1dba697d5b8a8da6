#pragma once
/// @file
/// Contacts of the current step, read from Bullet's persistent manifolds; and the overlap test
/// for objects that would start inside the robot.
#include <string>
#include <vector>

#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>

#include "body_tag.hpp"
#include "object_manager.hpp"
#include "robot_multibody.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::bullet_world {

/// The deepest interpenetration of a step.
struct Penetration {
  double depth = 0.0;  ///< [m], >= 0
  BodyTag a, b;
};

/// "link 'r_hand'" or "object 'ball'".
std::string body_name(const BodyTag& tag, const robot::RobotModel& model,
                      const ObjectManager& objects);

/// Fills `out` with the manifold points closer than `max_distance` [m] (touching or
/// penetrating). A link is always side a when one body is a link; otherwise the lower index is.
/// normal_force = applied impulse / dt [N]; between a kinematic object and immovable robot
/// geometry (the fixed base, a locked robot), where the solver applies no impulse, it is
/// `kinematic_stiffness` [N/m] × penetration depth [m] instead. `link_poses`: model link poses
/// of this step. Links folded into a rigid group are named through the compound child index of
/// the point. Returns the deepest penetration among the points the solver resolves (a kinematic
/// object pushed into immovable geometry is not a physics failure).
Penetration extract_contacts(btDispatcher& dispatcher, const RobotMultiBody& robot,
                             const std::vector<Eigen::Isometry3d>& link_poses,
                             const ObjectManager& objects, double dt, double max_distance,
                             double kinematic_stiffness, Contacts& out);

/// The robot link that `object` overlaps most, and by how much.
struct RobotOverlap {
  int link = -1;       ///< -1: no overlap
  double depth = 0.0;  ///< [m]
};
RobotOverlap deepest_robot_overlap(btCollisionWorld& world, const RobotMultiBody& robot,
                                   btCollisionObject& object);

}  // namespace somasim::bullet_world
