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
  bool immovable = false;  ///< the fixed base, static robot geometry, static and kinematic objects,
                           ///< kinematic robot links
  bool kinematic = false;  ///< moved along a prescribed path, not by dynamics: a kinematic object
                           ///< or a link of a kinematic robot (`joint_motion: kinematic`)
};

/// Pairs the solver never sees (both bodies immovable) that must still make contacts: a
/// kinematic object touching a robot link (immovable geometry: the fixed base, a locked or a
/// kinematic robot), or a kinematic robot link touching any object. Robot link pairs are
/// decided by the self-collision filter.
inline bool kinematic_meets_link(const BodyTag& a, const BodyTag& b) {
  const auto moving_link_meets_object = [](const BodyTag& link, const BodyTag& other) {
    return link.kind == BodyKind::kLink && link.kinematic && other.kind == BodyKind::kObject;
  };
  return (a.kinematic && b.kind == BodyKind::kLink) || (b.kinematic && a.kind == BodyKind::kLink) ||
         moving_link_meets_object(a, b) || moving_link_meets_object(b, a);
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
