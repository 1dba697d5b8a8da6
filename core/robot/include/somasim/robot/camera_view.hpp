#pragma once
/// @file
/// Whether the robot's cameras can see a point: inside a camera's image and not hidden behind
/// the robot's own links (e.g. to present an object where the robot's eyes can see it coming).
/// Camera frame as robot::Camera (z optical axis, x image-right, y image-down); points and link
/// poses in the root frame [m].
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// root <- camera frame of `camera`, the robot posed by `link_poses` (root <- link, model link
/// order).
Eigen::Isometry3d camera_pose(const Camera& camera,
                              const std::vector<Eigen::Isometry3d>& link_poses);

/// The pixel (u, v) [px] where `point` [m, root] projects in `camera` at `pose` (root <- camera);
/// nullopt when the point is not in front of the near plane.
std::optional<Eigen::Vector2d> project_point(const Camera& camera, const Eigen::Isometry3d& pose,
                                             const Eigen::Vector3d& point);

/// Whether pixel `uv` [px] lies at least `margin_px` [px] inside the image of `camera` (pixel
/// centres at integers: the image spans [-0.5, width - 0.5] x [-0.5, height - 0.5]).
bool inside_image(const Camera& camera, const Eigen::Vector2d& uv, double margin_px);

/// Why a point is not seen by a camera (kSeen when it is).
enum class Sight : std::uint8_t {
  kSeen,         ///< in the image and nothing of the robot in between
  kBehind,       ///< behind the camera, before its near plane or beyond its far plane
  kOutOfImage,   ///< projects outside the image (less `margin_px` from its border)
  kHiddenByBody  ///< the line of sight meets a robot link
};

/// Whether `camera` sees `point` [m, root], the robot posed by `link_poses`: in front of it,
/// projecting at least `margin_px` [px] inside the image, and the segment from the optical
/// centre to the point clear of every collision shape of the robot (links whose shapes come
/// within 3 cm of the optical centre, the eye and head that carry the camera, are not tested;
/// meshes are not tested). With a wrong number of poses: kBehind (nothing is seen).
Sight camera_sight(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                   const Camera& camera, const Eigen::Vector3d& point, double margin_px);

/// "seen", "behind the camera", "outside the image" or "hidden by the robot's body".
const char* sight_name(Sight sight);

}  // namespace somasim::robot
