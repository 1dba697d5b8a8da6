#pragma once
/// @file
/// A conservative test of whether a point is clear of the robot's collision geometry, e.g. to
/// start a thrown object outside the robot.
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// True when `point` [m, root frame] is farther than `margin` [m] from every collision shape of
/// the robot posed by `link_poses` (root <- link, model link order). Each shape is bounded by a
/// sphere around its origin (sphere: r; box: half diagonal; cylinder: hypot(r, length/2);
/// capsule: r + length/2; mesh: not bounded), so the test errs on the side of "not clear".
/// With a wrong number of poses it returns true (nothing to test against).
bool point_clear_of_robot(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                          const Eigen::Vector3d& point, double margin);

/// Distance [m] from `point` (in the frame of the link that owns `shape`) to the primitive
/// `shape`: positive outside, negative inside (the depth). Meshes: +infinity (not modelled).
double distance_to_shape(const Geometry& shape, const Eigen::Vector3d& point);

/// True when the straight segment `from` -> `to` [m, root frame], sampled every 2 mm, stays
/// farther than `margin` [m] from every collision shape of the links not in `ignored_links`
/// (model link indices), the robot posed by `link_poses`; meshes are not tested. E.g. the path
/// of an object's centre to the taxel it is aimed at, margin = the object's bounding radius, the
/// aimed link ignored: nothing else is in its way. With a wrong number of poses it returns true.
bool segment_clear_of_robot(const RobotModel& model,
                            const std::vector<Eigen::Isometry3d>& link_poses,
                            const Eigen::Vector3d& from, const Eigen::Vector3d& to, double margin,
                            std::span<const int> ignored_links = {});

}  // namespace somasim::robot
