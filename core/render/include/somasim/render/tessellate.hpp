#pragma once
/// @file
/// Triangle meshes of the primitive shapes of robot and object geometry.
///
/// Every mesh is in the primitive's own frame, with the conventions of somasim::robot::Geometry:
/// boxes are centred on the origin with full extents `size` along x, y, z; spheres are centred
/// on the origin; cylinders and capsules are centred on the origin with their axis along z, the
/// cylindrical part spanning z in [-length/2, length/2] (a capsule adds hemispheres of the same
/// radius at both ends). Units: metres. Vertices lie on the true surface (the mesh is inscribed);
/// normals are the true surface normals at the vertices (flat for box faces and cylinder caps,
/// smooth on curved parts). Triangles are counter-clockwise seen from outside.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "somasim/robot/geometry.hpp"

namespace somasim::render {

/// Indexed triangle mesh: 3 indices per triangle into `positions` / `normals` (same length).
struct TriangleMesh {
  std::vector<Eigen::Vector3f> positions;  ///< [m], primitive frame
  std::vector<Eigen::Vector3f> normals;    ///< unit, primitive frame
  std::vector<std::uint32_t> indices;

  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// Axis-aligned bounds of a mesh's vertices (min = max = 0 for an empty mesh).
struct Bounds {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
};
Bounds bounds(const TriangleMesh& mesh);

/// Box of full extents `size` (x, y, z) [m]: 6 faces of 2 triangles, 24 vertices.
TriangleMesh tessellate_box(const Eigen::Vector3d& size);

/// UV sphere of `radius` [m] with `segments` (>= 3) around the z axis and segments / 2 (>= 2)
/// rings from pole to pole.
TriangleMesh tessellate_sphere(double radius, int segments);

/// Closed cylinder of `radius` [m] along z, `length` [m] long, `segments` (>= 3) around.
TriangleMesh tessellate_cylinder(double radius, double length, int segments);

/// Capsule: cylinder of `radius` and `length` along z plus two hemispheres; `segments` (>= 3)
/// around z, and max(1, segments / 4) rings per hemisphere.
TriangleMesh tessellate_capsule(double radius, double length, int segments);

/// The mesh of a primitive robot::Geometry in the shape's own frame (its `origin` is NOT
/// applied: the caller poses the mesh with root <- link * geometry.origin). Throws
/// somasim::InputError for mesh geometry (mesh files are not tessellated here) and for
/// segments < 3.
TriangleMesh tessellate(const robot::Geometry& geometry, int segments);

}  // namespace somasim::render
