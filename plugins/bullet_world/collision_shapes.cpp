#include "collision_shapes.hpp"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include "bullet_math.hpp"
#include "somasim/robot/mesh_loader.hpp"

namespace somasim::bullet_world {

ShapeStore::ShapeStore() = default;
ShapeStore::~ShapeStore() = default;

btCollisionShape* ShapeStore::keep(std::unique_ptr<btCollisionShape> shape) {
  shapes_.push_back(std::move(shape));
  return shapes_.back().get();
}

btCollisionShape* ShapeStore::make(const robot::Geometry& g, MeshUse mesh_use) {
  using robot::GeometryType;
  switch (g.type) {
    case GeometryType::Sphere:
      return keep(std::make_unique<btSphereShape>(g.radius));
    case GeometryType::Box: {
      // Bullet's default margin (4 cm) is larger than the iCub's fingers: use a small one.
      auto box = std::make_unique<btBoxShape>(to_bt(Eigen::Vector3d(0.5 * g.size)));
      box->setMargin(kShapeMargin);
      return keep(std::move(box));
    }
    case GeometryType::Cylinder: {
      auto cyl = std::make_unique<btCylinderShapeZ>(btVector3(g.radius, g.radius, 0.5 * g.length));
      cyl->setMargin(kShapeMargin);
      return keep(std::move(cyl));
    }
    case GeometryType::Capsule:
      return keep(std::make_unique<btCapsuleShapeZ>(g.radius, g.length));
    case GeometryType::Mesh: {
      const std::string key = g.mesh_file + "|" + std::to_string(g.mesh_scale.x()) + "," +
                              std::to_string(g.mesh_scale.y()) + "," +
                              std::to_string(g.mesh_scale.z()) +
                              (mesh_use == MeshUse::kTriangles ? "|tri" : "|hull");
      if (auto it = mesh_cache_.find(key); it != mesh_cache_.end()) return it->second;
      const robot::TriangleMesh mesh = robot::load_triangle_mesh(g.mesh_file, g.mesh_scale);
      btCollisionShape* shape = nullptr;
      if (mesh_use == MeshUse::kConvexHull) {
        auto hull = std::make_unique<btConvexHullShape>();
        for (const auto& v : mesh.vertices) hull->addPoint(to_bt(v), false);
        hull->recalcLocalAabb();
        hull->setMargin(kShapeMargin);
        shape = keep(std::move(hull));
      } else {
        auto tri = std::make_unique<btTriangleMesh>(true, false);
        for (const auto& t : mesh.triangles)
          tri->addTriangle(to_bt(mesh.vertices[t[0]]), to_bt(mesh.vertices[t[1]]),
                           to_bt(mesh.vertices[t[2]]));
        shape = keep(std::make_unique<btBvhTriangleMeshShape>(tri.get(), true));
        meshes_.push_back(std::move(tri));
      }
      mesh_cache_[key] = shape;
      return shape;
    }
  }
  return nullptr;
}

btCompoundShape* ShapeStore::make_compound(const std::vector<robot::Geometry>& shapes,
                                           const Eigen::Isometry3d& link_in_body,
                                           MeshUse mesh_use) {
  auto compound = std::make_unique<btCompoundShape>(false, static_cast<int>(shapes.size()));
  for (const auto& g : shapes)
    compound->addChildShape(to_bt(link_in_body * g.origin), make(g, mesh_use));
  btCompoundShape* out = compound.get();
  keep(std::move(compound));
  return out;
}

}  // namespace somasim::bullet_world
