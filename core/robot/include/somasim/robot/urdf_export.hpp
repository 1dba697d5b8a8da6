#pragma once
/// @file
/// Writing any somasim robot as a URDF (`somasim robot export-urdf`), so that other tools (ROS,
/// Gazebo, MuJoCo's importer, Drake) see the same robot, and what URDF cannot say as a YAML
/// overlay that extends it.
///
/// What changes form, not meaning: a joint's `offset` is folded into its origin (URDF has none;
/// q keeps its meaning), a joint's `post` transform becomes a fixed joint to the real child after
/// an extra link named `<joint>_axis_frame`, a capsule becomes a cylinder and two spheres, mesh
/// files are written relative to the URDF's directory (or absolute), joints with limits of 10³ rad
/// or more are continuous. Loading the URDF (and overlay) back gives the same link poses for every
/// q, the same masses, centres of mass and inertias, and the same shapes. DH chains become chains
/// along the tree (base link and tip: the same joints), in the overlay.
#include <filesystem>
#include <string>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// The robot as a URDF document (UTF-8 XML). Mesh files are written relative to `mesh_base`
/// (the directory the URDF will be in) when it is given, else as absolute paths.
std::string to_urdf(const RobotModel& model, const std::filesystem::path& mesh_base = {});

/// A robot-description overlay (YAML) that `extends: urdf_file` and adds the model's frames,
/// cameras, skin patches and chains (as chains along the tree).
std::string urdf_overlay(const RobotModel& model, const std::string& urdf_file);

}  // namespace somasim::robot
