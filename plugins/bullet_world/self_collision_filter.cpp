#include "self_collision_filter.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include "body_tag.hpp"
#include "somasim/robot/self_collision.hpp"

namespace somasim::bullet_world {

SelfCollisionFilter::SelfCollisionFilter(const robot::RobotModel& model,
                                         const std::vector<bool>& locked)
    : adjacent_(robot::collision_exempt_links(model, locked)) {}

bool SelfCollisionFilter::needBroadphaseCollision(btBroadphaseProxy* proxy0,
                                                  btBroadphaseProxy* proxy1) const {
  // Bullet's default group/mask test first.
  if (!(proxy0->m_collisionFilterGroup & proxy1->m_collisionFilterMask) ||
      !(proxy1->m_collisionFilterGroup & proxy0->m_collisionFilterMask))
    return false;
  const auto* a = static_cast<const btCollisionObject*>(proxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(proxy1->m_clientObject);
  const BodyTag ta = tag_of(*a), tb = tag_of(*b);
  if (ta.kind == BodyKind::kLink && tb.kind == BodyKind::kLink) {
    if (adjacent_[ta.index][tb.index]) return false;
    // Two immovable links touch only when one moves kinematically (reported, not solved).
    return !(ta.immovable && tb.immovable) || ta.kinematic || tb.kinematic;
  }
  if (ta.immovable && tb.immovable) return kinematic_meets_link(ta, tb);
  return true;
}

}  // namespace somasim::bullet_world
