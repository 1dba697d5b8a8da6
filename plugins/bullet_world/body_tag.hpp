#pragma once
/// @file
/// What a Bullet collision object stands for: a robot link or an object of the world. Stored in
/// the object's user indices so that contacts and filters can name the bodies.
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

namespace somasim::bullet_world {

enum class BodyKind { kNone = 0, kLink = 1, kObject = 2 };

struct BodyTag {
  BodyKind kind = BodyKind::kNone;
  int index = -1;          ///< model link index or object index
  bool immovable = false;  ///< the fixed base, static robot geometry, static and kinematic objects
  bool kinematic = false;  ///< a kinematic object (moved along a prescribed path, not by dynamics)
};

/// Pairs the solver never sees (both bodies immovable) that must still make contacts: a
/// kinematic object touching the robot's immovable geometry (the fixed base, a locked robot).
inline bool kinematic_meets_link(const BodyTag& a, const BodyTag& b) {
  return (a.kinematic && b.kind == BodyKind::kLink) || (b.kinematic && a.kind == BodyKind::kLink);
}

inline void set_tag(btCollisionObject& object, const BodyTag& tag) {
  object.setUserIndex(static_cast<int>(tag.kind));
  object.setUserIndex2(tag.index);
  object.setUserIndex3((tag.immovable ? 1 : 0) | (tag.kinematic ? 2 : 0));
}

inline BodyTag tag_of(const btCollisionObject& object) {
  const int flags = object.getUserIndex3();
  return {static_cast<BodyKind>(object.getUserIndex()), object.getUserIndex2(), (flags & 1) != 0,
          (flags & 2) != 0};
}

}  // namespace somasim::bullet_world
