#pragma once
/// @file
/// The `initial_posture_deg` parameter: "joint: value, joint: value, ..." (degrees; prismatic
/// joints in metres). Joints not listed start at 0 clamped into their limits.
#include <string>

#include <Eigen/Core>

#include "somasim/robot/robot_model.hpp"

namespace somasim::bullet_world {

/// Joint values (model dof order) [rad]/[m]. Throws InputError with a message to be prefixed
/// by the parameter's location: unknown joint (with a suggestion), a value outside the limits,
/// malformed pairs.
Eigen::VectorXd parse_posture(const std::string& text, const robot::RobotModel& model);

}  // namespace somasim::bullet_world
