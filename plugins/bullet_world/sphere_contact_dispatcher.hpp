#pragma once
/// @file
/// The collision dispatcher of bullet_world: Bullet's, except that a sphere touching a convex
/// shape (or a convex child of a compound) keeps one contact point per step. Bullet's persistent
/// manifolds cache up to four points per pair so that flat faces rest stably; a sphere meets a
/// convex shape at a single point, and the points Bullet caches while it rests or rolls lie within
/// a millimetre of that one (a ball on the iCub's forearm: four points 0.5–1.1 mm apart). Each
/// would be solved as a contact of its own, with its friction and rolling-friction rows, as if the
/// sphere touched over a patch. After the narrow phase every such manifold keeps its deepest point
/// (with its cached impulses, so the solver's warm start is unchanged); other pairs keep Bullet's
/// manifolds.
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>

namespace somasim::bullet_world {

class SphereContactDispatcher : public btCollisionDispatcher {
 public:
  using btCollisionDispatcher::btCollisionDispatcher;

  void dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                 btDispatcher* dispatcher) override;
};

}  // namespace somasim::bullet_world
