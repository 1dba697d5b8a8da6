#pragma once
/// @file
/// Objects of the world as geometry: what an ObjectSpawn (or an ObjectStates entry) describes,
/// for the physics, a renderer or an evaluator, and the checks a spawn request must pass.
#include <string>

#include <Eigen/Core>

#include "somasim/robot/geometry.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::robot {

/// The geometry of an object of `shape` with `size` as in ObjectSpawn::size (sphere: radius;
/// box: half extents; cylinder: radius, half height; mesh: per-axis scale, 0 meaning 1) [m],
/// in the object's frame (the shape's centre; a mesh: its file's origin).
Geometry object_geometry(ObjectShape shape, const Eigen::Vector3d& size, const std::string& mesh);

/// What is wrong with a spawn request ("" when nothing): sizes, mass, non-finite values.
std::string spawn_problem(const ObjectSpawn& spawn);

}  // namespace somasim::robot
