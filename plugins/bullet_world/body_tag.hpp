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
  bool immovable = false;  ///< the fixed base, static and kinematic objects
};

inline void set_tag(btCollisionObject& object, const BodyTag& tag) {
  object.setUserIndex(static_cast<int>(tag.kind));
  object.setUserIndex2(tag.index);
  object.setUserIndex3(tag.immovable ? 1 : 0);
}

inline BodyTag tag_of(const btCollisionObject& object) {
  return {static_cast<BodyKind>(object.getUserIndex()), object.getUserIndex2(),
          object.getUserIndex3() == 1};
}

}  // namespace somasim::bullet_world
