#pragma once
/// @file
/// Reading robot descriptions (YAML). The format is documented in assets/robots/README.md.
/// Every error names the file, line and column, the item (link, joint, chain, ...) and the key,
/// says what was expected and suggests the nearest valid name; all errors of a file are
/// collected and thrown together as one InputError.
#include <filesystem>
#include <memory>
#include <string>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// Loads a robot description file: somasim's YAML, or a URDF (extension .urdf). Relative paths
/// inside it (extends, mesh files) are relative to the file's directory.
RobotModel load_robot_model(const std::filesystem::path& file);

/// The same, as a shared immutable model (for tools and tests; plugins get the experiment's
/// robots through experiment_robot.hpp, which loads each once per run).
std::shared_ptr<const RobotModel> load_robot_model_shared(const std::filesystem::path& file);

/// Parses description text; `display_name` is used in messages, `base_dir` resolves relative
/// paths.
RobotModel parse_robot_model(const std::string& text, const std::string& display_name,
                             const std::filesystem::path& base_dir);

/// Parses URDF text (read with urdfdom; assets/robots/README.md says what is kept);
/// `display_name` names it in messages (with the element's line), `base_dir` resolves relative
/// mesh files. Missing meshes are errors.
RobotModel parse_urdf_robot_model(const std::string& xml, const std::string& display_name,
                                  const std::filesystem::path& base_dir);

}  // namespace somasim::robot
