#pragma once
/// @file
/// Postures written as text, as in experiment parameters: "joint: value, joint: value, ..."
/// (degrees; prismatic joints in metres). Joints not listed are 0 clamped into their limits.
#include <string>

#include <Eigen/Core>

#include "somasim/robot/robot_model.hpp"

namespace somasim::control {

/// Joint values (model dof order) [rad]/[m]. InputError (to be prefixed with the parameter's
/// location) for malformed pairs ("expected 'joint: value' pairs separated by commas, got 'x'"),
/// an unknown joint (with a suggestion) or a value outside the joint's limits.
Eigen::VectorXd parse_posture_deg(const std::string& text, const robot::RobotModel& model);

}  // namespace somasim::control
