#pragma once
/// @file
/// One immutable RobotModel per description file, shared by every plugin of a process
/// (DESIGN.md §6: the world, the skin and the controllers of a run see the same model).
#include <filesystem>
#include <memory>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// Loads `file` once (keyed by its canonical path) and returns the shared model; later calls
/// return the same instance. Thread-safe. Throws InputError like load_robot_model().
std::shared_ptr<const RobotModel> shared_robot_model(const std::filesystem::path& file);

}  // namespace somasim::robot
