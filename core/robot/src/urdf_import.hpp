#pragma once
// Internal: URDF robots (read with urdfdom) turned into somasim's robot description, so that the
// YAML loader builds and validates them like any other robot (and a YAML overlay can `extends`
// them to add cameras, skin and frames).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace somasim::robot::detail {

/// What to do with a mesh file that cannot be found: report it (with every other missing mesh),
/// leave the shape out, or (visual meshes) draw the link's collision shapes that do exist instead.
enum class MissingMeshes { kError, kSkip, kCollision };

/// "error", "skip" or "collision"; nullopt for anything else.
std::optional<MissingMeshes> parse_missing_meshes(const std::string& text);

/// Whether `file` is a URDF (its extension is .urdf, any case).
bool is_urdf_file(const std::filesystem::path& file);

/// Where `package://NAME/...` is looked for, in order: the directories of SOMASIM_RESOURCE_PATH
/// (colon-separated; `somasim --resource-path` prepends to it), then of ROS_PACKAGE_PATH. A
/// package NAME is the directory NAME under one of them.
std::vector<std::filesystem::path> resource_path();

/// The URDF `xml` (read from `display`, its directory `dir`) as somasim robot-description YAML:
/// every link (inertial, collision and visual shapes, material colours) and joint (revolute,
/// continuous, prismatic, fixed; limits) in the file's order, and empty `frames`, `cameras`,
/// `skin` and `chains` maps for an overlay's `set`. Throws InputError naming `display`, the line
/// and the element for malformed XML, a joint whose parent or child link is missing, a link with
/// two parents, more than one root, a joint cycle, a floating or planar joint, a negative mass, an
/// inertia that is not positive definite, limits with lower > upper, meshes that are missing or
/// unreadable (all of them in one message, unless `missing` says otherwise) and unknown
/// `package://` names (with the search path).
std::string urdf_to_description(const std::string& xml, const std::string& display,
                                const std::filesystem::path& dir,
                                MissingMeshes missing = MissingMeshes::kError);

}  // namespace somasim::robot::detail
