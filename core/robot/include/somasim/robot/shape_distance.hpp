#pragma once
/// @file
/// The distance between two convex primitive shapes of a robot (e.g. how far apart two
/// fingertips' surfaces are), by alternating projections between the two solids.
#include <Eigen/Geometry>

#include "somasim/robot/geometry.hpp"

namespace somasim::robot {

/// Distance [m] between the surfaces of the primitives `a` and `b` (sphere, box, cylinder,
/// capsule), posed by the poses of the links that own them (`a_link`, `b_link`: root <- link;
/// each shape's `origin` is in its link's frame): 0 when they touch or overlap (within 1e-9 m),
/// +infinity when either is a mesh. Alternating projections onto the two convex solids from the
/// centre of `a` converge to a closest pair; at most 1,000 rounds, stopped when a round moves the
/// points less than 1e-12 m.
double shape_distance(const Geometry& a, const Eigen::Isometry3d& a_link, const Geometry& b,
                      const Eigen::Isometry3d& b_link);

}  // namespace somasim::robot
