#pragma once
/// @file
/// Joint values written as text, "joint: value, joint: value, ...": revolute joints in degrees,
/// prismatic joints in metres. Shared by every plugin that takes such a parameter (postures of
/// the world and the controllers, believed-kinematics offsets), so the syntax and the error
/// messages are the same everywhere. Error messages are meant to be prefixed by where the text
/// came from (the parameter's location).
#include <string>

#include <Eigen/Core>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// Per-dof offsets (model dof order) [rad] (prismatic: [m]) from "joint: value, ..." text;
/// joints not named are 0, an empty text gives all zeros. Throws InputError for:
///   - an entry without a colon: "expected 'joint: value', got 'x' (entries separated by ',')"
///   - an unknown joint: "unknown joint 'l_elbw' (did you mean 'l_elbow'?) (movable joints of
///     the robot)"
///   - a bad value: "joint 'l_elbow': expected a number [deg], got 'abc'" ([m] for prismatic)
///   - a joint named twice: "joint 'l_elbow' is given twice"
Eigen::VectorXd parse_joint_offsets(const RobotModel& model, const std::string& text);

/// A posture: joint values (model dof order) [rad]/[m]; joints not named are 0 clamped into
/// their limits. The same syntax and errors as parse_joint_offsets, and a value outside the
/// joint's limits: "joint 'l_elbow': 200 deg is outside the limits [15, 105]".
Eigen::VectorXd parse_posture_deg(const RobotModel& model, const std::string& text);

}  // namespace somasim::robot
