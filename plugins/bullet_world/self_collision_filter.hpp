#pragma once
/// @file
/// Which body pairs Bullet tests for collision. Self-collision is on between all robot links
/// except adjacent ones (robot::collision_exempt_links: the same rigid group, or a group and its
/// nearest ancestor group with geometry); immovable bodies (fixed base, static robot, static and
/// kinematic objects) never collide with each other, except a kinematic object with a robot link
/// (the contact is reported with a penetration force, contact_extraction.hpp).
#include <vector>

#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>

#include "somasim/robot/robot_model.hpp"

namespace somasim::bullet_world {

class SelfCollisionFilter : public btOverlapFilterCallback {
 public:
  /// `locked`: per dof, joints locked at their initial value (empty: none).
  explicit SelfCollisionFilter(const robot::RobotModel& model,
                               const std::vector<bool>& locked = {});

  /// True when links `a` and `b` (model indices) are never tested against each other.
  bool adjacent(int a, int b) const { return adjacent_[a][b]; }

  bool needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override;

 private:
  std::vector<std::vector<bool>> adjacent_;
};

}  // namespace somasim::bullet_world
