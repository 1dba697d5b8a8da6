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

// The tag of a manifold body with a link resolved to the model link of compound child `child`.
BodyTag resolved(BodyTag tag, const RobotMultiBody& robot, int child) {
  if (tag.kind == BodyKind::kLink) tag.index = robot.model_link(tag.index, child);
  return tag;
}
}  // namespace

Penetration extract_contacts(btDispatcher& dispatcher, const RobotMultiBody& robot,
                             const std::vector<Eigen::Isometry3d>& link_poses,
                             const ObjectManager& objects, double dt, double max_distance,
                             double kinematic_stiffness, Contacts& out) {
  out.points.clear();
  Penetration deepest;
  const int num_manifolds = dispatcher.getNumManifolds();
  for (int m = 0; m < num_manifolds; ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const BodyTag body0 = tag_of(*manifold->getBody0()), body1 = tag_of(*manifold->getBody1());
    const bool unsolved = body0.immovable && body1.immovable;  // kinematic_meets_link
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      const double distance = pt.getDistance();
      if (distance >= max_distance) continue;
      const BodyTag t0 = resolved(body0, robot, pt.m_index0);
      const BodyTag t1 = resolved(body1, robot, pt.m_index1);
      const bool swap = !goes_first(t0, t1);
      const BodyTag& ta = swap ? t1 : t0;
      const BodyTag& tb = swap ? t0 : t1;
      if (!unsolved && -distance > deepest.depth) deepest = {-distance, ta, tb};
      Contact c;
      set_side(c, true, ta);
      set_side(c, false, tb);
      c.point = to_eigen(swap ? pt.getPositionWorldOnB() : pt.getPositionWorldOnA());
      c.normal = to_eigen(pt.m_normalWorldOnB);
      if (swap) c.normal = -c.normal;
      const Eigen::Isometry3d a_pose =
          ta.kind == BodyKind::kLink ? link_poses[ta.index] : objects.pose(ta.index);
      c.point_in_a = a_pose.inverse() * c.point;
      c.normal_force = unsolved ? kinematic_stiffness * std::max(0.0, -distance)
                                : std::max(0.0, pt.getAppliedImpulse() / dt);
      out.points.push_back(c);
    }
  }
  return deepest;
}

namespace {
struct DeepestLinkCallback : btCollisionWorld::ContactResultCallback {
  explicit DeepestLinkCallback(const RobotMultiBody& r) : robot(r) {}
  const RobotMultiBody& robot;
  RobotOverlap result;
  bool needsCollision(btBroadphaseProxy* proxy) const override {
    return tag_of(*static_cast<const btCollisionObject*>(proxy->m_clientObject)).kind ==
           BodyKind::kLink;
  }
  btScalar addSingleResult(btManifoldPoint& pt, const btCollisionObjectWrapper* w0, int, int index0,
                           const btCollisionObjectWrapper* w1, int, int index1) override {
    const BodyTag t0 = resolved(tag_of(*w0->getCollisionObject()), robot, index0);
    const BodyTag t1 = resolved(tag_of(*w1->getCollisionObject()), robot, index1);
    const BodyTag& link = t0.kind == BodyKind::kLink ? t0 : t1;
    if (link.kind == BodyKind::kLink && -pt.getDistance() > result.depth)
      result = {link.index, -pt.getDistance()};
    return 0;
  }
};
}  // namespace

RobotOverlap deepest_robot_overlap(btCollisionWorld& world, const RobotMultiBody& robot,
                                   btCollisionObject& object) {
  DeepestLinkCallback callback(robot);
  callback.m_closestDistanceThreshold = 0;
  world.contactTest(&object, callback);
  return callback.result;
}

}  // namespace somasim::bullet_world
