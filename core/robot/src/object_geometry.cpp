#include "somasim/robot/object_geometry.hpp"

#include <cmath>

#include <fmt/format.h>

namespace somasim::robot {
namespace {

bool finite(const Eigen::Isometry3d& t) {
  return t.matrix().allFinite();
}

}  // namespace

Geometry object_geometry(ObjectShape shape, const Eigen::Vector3d& size, const std::string& mesh) {
  Geometry g;
  switch (shape) {
    case ObjectShape::kSphere:
      g.type = GeometryType::Sphere;
      g.radius = size.x();
      break;
    case ObjectShape::kBox:
      g.type = GeometryType::Box;
      g.size = 2.0 * size;
      break;
    case ObjectShape::kCylinder:
      g.type = GeometryType::Cylinder;
      g.radius = size.x();
      g.length = 2.0 * size.y();
      break;
    case ObjectShape::kMesh:
      g.type = GeometryType::Mesh;
      g.mesh_file = mesh;
      for (int i = 0; i < 3; ++i) g.mesh_scale[i] = size[i] > 0 ? size[i] : 1.0;
      break;
  }
  return g;
}

std::string spawn_problem(const ObjectSpawn& s) {
  if (!finite(s.pose) || !s.linear_velocity.allFinite() || !s.size.allFinite() ||
      !std::isfinite(s.mass))
    return "has a non-finite pose, velocity, size or mass";
  switch (s.shape) {
    case ObjectShape::kSphere:
      if (s.size.x() <= 0) return fmt::format("sphere radius must be > 0 m, got {}", s.size.x());
      break;
    case ObjectShape::kBox:
      if ((s.size.array() <= 0).any())
        return fmt::format("box half extents must be > 0 m, got [{}, {}, {}]", s.size.x(),
                           s.size.y(), s.size.z());
      break;
    case ObjectShape::kCylinder:
      if (s.size.x() <= 0 || s.size.y() <= 0)
        return fmt::format("cylinder radius and half height must be > 0 m, got {} and {}",
                           s.size.x(), s.size.y());
      break;
    case ObjectShape::kMesh:
      if (s.mesh.empty()) return "mesh object without a mesh file";
      if ((s.size.array() < 0).any()) return "mesh scale must not be negative";
      break;
  }
  if ((s.motion == ObjectMotion::kDynamic || s.motion == ObjectMotion::kGuided) && s.mass <= 0)
    return fmt::format("dynamic object mass must be > 0 kg, got {}", s.mass);
  return "";
}

}  // namespace somasim::robot
