#pragma once
/// @file
/// Bullet collision shapes from the robot description's geometry (and objects' shapes), owned by
/// a ShapeStore that outlives every body using them.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>

#include <Eigen/Geometry>

#include "somasim/robot/geometry.hpp"

namespace somasim::bullet_world {

/// How a mesh is used: convex hull (moving bodies) or exact triangles (static bodies only).
enum class MeshUse { kConvexHull, kTriangles };

/// Collision margin of boxes, cylinders and hulls [m] (spheres and capsules have none).
inline constexpr double kShapeMargin = 0.0005;

class ShapeStore {
 public:
  ShapeStore();
  ~ShapeStore();
  ShapeStore(const ShapeStore&) = delete;
  ShapeStore& operator=(const ShapeStore&) = delete;

  /// The shape of one geometry, centred as the geometry describes (its `origin` not applied).
  /// Meshes are loaded once per (file, scale, use).
  btCollisionShape* make(const robot::Geometry& geometry, MeshUse mesh_use);
  /// A compound of `shapes`, each placed at `frame_from_link · origin` (frame: the body frame
  /// relative to the link frame, e.g. the principal-axes frame at the centre of mass).
  btCompoundShape* make_compound(const std::vector<robot::Geometry>& shapes,
                                 const Eigen::Isometry3d& link_in_body, MeshUse mesh_use);

 private:
  btCollisionShape* keep(std::unique_ptr<btCollisionShape> shape);
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btTriangleMesh>> meshes_;
  std::map<std::string, btCollisionShape*> mesh_cache_;
};

}  // namespace somasim::bullet_world
