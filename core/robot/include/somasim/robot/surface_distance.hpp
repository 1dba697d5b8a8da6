#pragma once
/// @file
/// Signed distance from a point to the surface of a presented object (e.g. how close a presented
/// object came to the skin): > 0 outside, < 0 inside (penetration depth). Exact for spheres, boxes
/// and cylinders (the world's kCylinder: axis along the object's local z); any other shape is
/// bounded by its bounding sphere, which gives a lower bound of the true distance (conservative for
/// "the object stayed away").
#include <Eigen/Geometry>

#include "somasim/robot/ports.hpp"

namespace somasim::robot {

/// What is known of an object's geometry.
struct ObjectGeometry {
  ObjectShape shape = ObjectShape::kMesh;          ///< kMesh here: unknown, use `bounding_radius`
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< as ObjectSpawn::size [m]
  double bounding_radius = 0.0;                    ///< [m], from ObjectStates::radius
};

/// Signed distance [m] from `point` to the surface of the object at `pose` (root <- object);
/// `point` in the root frame [m].
double surface_distance(const ObjectGeometry& geometry, const Eigen::Isometry3d& pose,
                        const Eigen::Vector3d& point);

}  // namespace somasim::robot
