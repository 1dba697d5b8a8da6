#pragma once
/// @file
/// A conservative test of whether a point is clear of the robot's collision geometry, e.g. to
/// start a thrown object outside the robot.
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

}  // namespace somasim::robot
