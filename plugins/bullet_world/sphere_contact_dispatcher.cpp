#include "sphere_contact_dispatcher.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace somasim::bullet_world {
namespace {

bool is_sphere(const btCollisionObject& body) {
  return body.getCollisionShape()->getShapeType() == SPHERE_SHAPE_PROXYTYPE;
}

// The convex shape of `body` that a contact point lies on: the body's own, or for a compound the
// child the point names (`child` is the point's index on that side).
bool touched_shape_is_convex(const btCollisionObject& body, int child) {
  const btCollisionShape* shape = body.getCollisionShape();
  if (shape->isCompound()) {
    const auto* compound = static_cast<const btCompoundShape*>(shape);
    if (child < 0 || child >= compound->getNumChildShapes()) return false;
    shape = compound->getChildShape(child);
  }
  return shape->isConvex();
}

// True when the manifold is a sphere against a convex shape (or a convex child of a compound).
bool sphere_meets_convex(const btPersistentManifold& manifold) {
  const btCollisionObject& a = *manifold.getBody0();
  const btCollisionObject& b = *manifold.getBody1();
  for (int p = 0; p < manifold.getNumContacts(); ++p) {
    const btManifoldPoint& pt = manifold.getContactPoint(p);
    const bool convex = (is_sphere(a) && touched_shape_is_convex(b, pt.m_index1)) ||
                        (is_sphere(b) && touched_shape_is_convex(a, pt.m_index0));
    if (!convex) return false;
  }
  return manifold.getNumContacts() > 0;
}

// Removes every point of `manifold` but its deepest (smallest distance; the first on ties).
void keep_deepest_point(btPersistentManifold& manifold) {
  int deepest = 0;
  for (int p = 1; p < manifold.getNumContacts(); ++p)
    if (manifold.getContactPoint(p).getDistance() < manifold.getContactPoint(deepest).getDistance())
      deepest = p;
  // The point is kept whole: its lifetime and last impulses warm-start the solver as before.
  const btManifoldPoint kept = manifold.getContactPoint(deepest);
  manifold.clearManifold();
  manifold.addManifoldPoint(kept);
}

}  // namespace

void SphereContactDispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairs,
                                                        const btDispatcherInfo& info,
                                                        btDispatcher* dispatcher) {
  btCollisionDispatcher::dispatchAllCollisionPairs(pairs, info, dispatcher);
  for (int m = 0; m < getNumManifolds(); ++m) {
    btPersistentManifold& manifold = *getManifoldByIndexInternal(m);
    if (manifold.getNumContacts() > 1 && sphere_meets_convex(manifold))
      keep_deepest_point(manifold);
  }
}

}  // namespace somasim::bullet_world
