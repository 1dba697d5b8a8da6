#pragma once
// Checks an image input of a vision plugin against the robot model's camera it should come
// from: rgb8, the camera's calibrated size, the camera's name (when the image carries one).
#include <string>

#include "somasim/render/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

/// Throws RunError naming `port`: "input 'P': expected an rgb8 image, got E", "input 'P': the
/// image is W × H px, but camera 'C' of robot 'R' is calibrated for W × H px (wire images of
/// that camera at its resolution)", "input 'P': the image comes from camera 'X', expected 'C'
/// (param cameras)".
void check_camera_image(const robot::RobotModel& model, const Image& image, const std::string& port,
                        const std::string& camera);

}  // namespace somasim::plugins
