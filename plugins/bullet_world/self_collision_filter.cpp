#include "self_collision_filter.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include "body_tag.hpp"

namespace somasim::bullet_world {

SelfCollisionFilter::SelfCollisionFilter(const robot::RobotModel& model,
                                         const std::vector<bool>& locked) {
  const int n = model.num_links();
  // Rigid group of each link: the link reached by walking up through fixed or locked joints
  // (the representative of rigid_groups.hpp).
  auto rigid = [&](int link) {
    const int j = model.link(link).parent_joint;
    if (j < 0) return false;
    const int dof = model.joint(j).dof;
    return dof < 0 || (!locked.empty() && locked[dof]);
  };
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) {
    int g = i;
    while (rigid(g)) g = model.link(g).parent_link;
    group[i] = g;
  }
  std::vector<bool> group_has_geometry(n, false);
  for (int i = 0; i < n; ++i)
    if (!model.link(i).collision.empty()) group_has_geometry[group[i]] = true;
  // Nearest ancestor group with geometry (-1 for none).
  std::vector<int> geometric_parent(n, -1);
  for (int i = 0; i < n; ++i) {
    int p = model.link(group[i]).parent_link;
    while (p >= 0 && !group_has_geometry[group[p]]) p = model.link(group[p]).parent_link;
    geometric_parent[i] = p >= 0 ? group[p] : -1;
  }
  adjacent_.assign(n, std::vector<bool>(n, false));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      adjacent_[a][b] = group[a] == group[b] || geometric_parent[a] == group[b] ||
                        geometric_parent[b] == group[a];
}

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
