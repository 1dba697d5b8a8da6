#pragma once
/// @file
/// Stereo triangulation through two posed pinhole cameras (somasim/render/camera.hpp: pixel
/// (u, v) conventions, camera frame x right, y down, z forward, `pose_root` = root <- camera).
/// Points are in the root frame [m].
#include <Eigen/Core>

#include "somasim/render/camera.hpp"

namespace somasim::vision {

/// The ray of a pixel: origin at the camera's optical centre, unit direction (root frame).
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      ///< [m], root frame
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit, root frame
};

/// The ray through the pixel position `uv` [px] (no distortion).
Ray pixel_ray(const render::Camera& camera, const Eigen::Vector2d& uv);

struct Triangulation {
  /// False when the rays are (nearly) parallel or the point is not in front of both cameras;
  /// the other fields are then meaningless.
  bool valid = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< midpoint of the rays' closest points [m]
  double ray_gap_m = 0.0;              ///< distance between the closest points of the two rays [m]
  double reprojection_error_px = 0.0;  ///< RMS over both cameras of |project(point) - uv| [px]
};

/// The point seen at `uv_a` by `a` and at `uv_b` by `b` (midpoint method: exact for rays that
/// meet; for rays that miss each other, the midpoint of their common perpendicular).
Triangulation triangulate(const render::Camera& a, const Eigen::Vector2d& uv_a,
                          const render::Camera& b, const Eigen::Vector2d& uv_b);

}  // namespace somasim::vision
