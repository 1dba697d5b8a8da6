#pragma once
/// @file
/// Collision/visual shapes of a link and the link's mass properties.
///
/// Units: [m], [kg], [kg·m²]. Every pose is expressed in the frame of the link that owns it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace somasim::robot {

enum class GeometryType { Sphere, Box, Cylinder, Capsule, Mesh };

/// "sphere", "box", "cylinder", "capsule", "mesh" (the names used in robot descriptions).
std::string_view geometry_type_name(GeometryType type);

/// One primitive shape (or a mesh file) fixed to a link.
struct Geometry {
  GeometryType type = GeometryType::Sphere;
  /// Pose of the shape in the link frame. Cylinders and capsules are centred on the origin with
  /// their axis along the shape's z; boxes are centred on the origin.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  double radius = 0.0;  ///< sphere, cylinder, capsule [m]
  double length = 0.0;  ///< cylinder, capsule: cylindrical part along z [m]
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< box: full extents along x, y, z [m]
  std::string mesh_file;  ///< mesh: absolute path (checked to exist and be readable at load)
  Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();  ///< mesh: per-axis scale
  /// Visual shapes only (`colour: [r, g, b]`, each in [0, 1]): the albedo the renderer draws
  /// this shape with, e.g. a coloured marker; nullopt = the link's colour (from its name).
  std::optional<Eigen::Vector3d> colour;
};

/// Volume of a primitive [m³]; 0 for meshes (their volume is unknown until loaded).
double volume(const Geometry& geometry);

/// Mass properties of a link.
struct Inertial {
  double mass = 0.0;                                  ///< [kg]; 0 only for massless frame links
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< centre of mass in the link frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the com, link axes [kg·m²]
};

/// Mass properties of a union of primitives (overlaps counted twice) of uniform `density`
/// [kg/m³]. Meshes contribute nothing.
Inertial inertial_from_geometry(const std::vector<Geometry>& shapes, double density);

}  // namespace somasim::robot
