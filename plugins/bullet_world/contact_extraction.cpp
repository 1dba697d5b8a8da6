#include "contact_extraction.hpp"

#include <algorithm>

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include "bullet_math.hpp"

namespace somasim::bullet_world {

std::string body_name(const BodyTag& tag, const robot::RobotModel& model,
                      const ObjectManager& objects) {
  switch (tag.kind) {
    case BodyKind::kLink:
      return "link '" + model.link(tag.index).name + "'";
    case BodyKind::kObject:
      return "object '" + objects.name(tag.index) + "'";
    case BodyKind::kNone:
      break;
  }
  return "an unknown body";
}

namespace {
// Order of sides: links first, then lower indices.
bool goes_first(const BodyTag& x, const BodyTag& y) {
  if (x.kind != y.kind) return x.kind == BodyKind::kLink;
  return x.index <= y.index;
}

void set_side(Contact& c, bool a_side, const BodyTag& tag) {
  int& link = a_side ? c.link_a : c.link_b;
  int& object = a_side ? c.object_a : c.object_b;
  (tag.kind == BodyKind::kLink ? link : object) = tag.index;
}
}  // namespace

Penetration extract_contacts(btDispatcher& dispatcher,
                             const std::vector<Eigen::Isometry3d>& link_poses,
                             const ObjectManager& objects, double dt, double max_distance,
                             Contacts& out) {
  out.points.clear();
  Penetration deepest;
  const int num_manifolds = dispatcher.getNumManifolds();
  for (int m = 0; m < num_manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const BodyTag t0 = tag_of(*manifold->getBody0()), t1 = tag_of(*manifold->getBody1());
    const bool swap = !goes_first(t0, t1);
    const BodyTag& ta = swap ? t1 : t0;
    const BodyTag& tb = swap ? t0 : t1;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      const double distance = pt.getDistance();
      if (distance >= max_distance) continue;
      if (-distance > deepest.depth) deepest = {-distance, ta, tb};
      Contact c;
      set_side(c, true, ta);
      set_side(c, false, tb);
      c.point = to_eigen(swap ? pt.getPositionWorldOnB() : pt.getPositionWorldOnA());
      c.normal = to_eigen(pt.m_normalWorldOnB);
      if (swap) c.normal = -c.normal;
      const Eigen::Isometry3d a_pose =
          ta.kind == BodyKind::kLink ? link_poses[ta.index] : objects.pose(ta.index);
      c.point_in_a = a_pose.inverse() * c.point;
      c.normal_force = std::max(0.0, pt.getAppliedImpulse() / dt);
      out.points.push_back(c);
    }
  }
  return deepest;
}

namespace {
struct DeepestLinkCallback : btCollisionWorld::ContactResultCallback {
  RobotOverlap result;
  bool needsCollision(btBroadphaseProxy* proxy) const override {
    return tag_of(*static_cast<const btCollisionObject*>(proxy->m_clientObject)).kind ==
           BodyKind::kLink;
  }
  btScalar addSingleResult(btManifoldPoint& pt, const btCollisionObjectWrapper* w0, int, int,
                           const btCollisionObjectWrapper* w1, int, int) override {
    const BodyTag t0 = tag_of(*w0->getCollisionObject()), t1 = tag_of(*w1->getCollisionObject());
    const BodyTag& link = t0.kind == BodyKind::kLink ? t0 : t1;
    if (link.kind == BodyKind::kLink && -pt.getDistance() > result.depth)
      result = {link.index, -pt.getDistance()};
    return 0;
  }
};
}  // namespace

RobotOverlap deepest_robot_overlap(btCollisionWorld& world, btCollisionObject& object) {
  DeepestLinkCallback callback;
  callback.m_closestDistanceThreshold = 0;
  world.contactTest(&object, callback);
  return callback.result;
}

}  // namespace somasim::bullet_world
