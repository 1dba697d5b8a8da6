#pragma once
/// @file
/// Pinhole camera: intrinsics, pose, the OpenGL matrices that render what it sees, and the
/// projection of points to pixels.
///
/// Camera frame (computer-vision convention): origin at the optical centre, x to the right of
/// the image, y down the image, z forward along the optical axis. `pose_root` is root <- camera.
///
/// Pixel coordinates (OpenCV convention): u to the right, v down, row 0 at the top of the image;
/// the centre of pixel (column c, row r) is at (u, v) = (c, r), so pixel (c, r) covers
/// [c - 0.5, c + 0.5) × [r - 0.5, r + 0.5). A point (x, y, z) of the camera frame, z > 0,
/// projects to u = fx x / z + cx, v = fy y / z + cy (no distortion).
///
/// OpenGL side: the view matrix maps root coordinates to GL eye coordinates (x right, y up,
/// z backward: the camera frame turned by 180° about x); the projection matrix maps eye
/// coordinates to clip coordinates so that window row 0 (the first row glReadPixels returns) is
/// the image's top row: read-backs need no flip. Because of that y flip, triangles that are
/// counter-clockwise in the scene are clockwise in the window.
#include <optional>
#include <string>

#include <Eigen/Geometry>

namespace somasim::render {

struct PinholeIntrinsics {
  int width = 0;       ///< [px]
  int height = 0;      ///< [px]
  double fx = 0.0;     ///< focal length along u [px]
  double fy = 0.0;     ///< focal length along v [px]
  double cx = 0.0;     ///< principal point u [px] ((width - 1) / 2 for a centred optical axis)
  double cy = 0.0;     ///< principal point v [px]
  double near = 0.01;  ///< near clipping distance along z [m], > 0
  double far = 10.0;   ///< far clipping distance along z [m], > near
};

/// Throws somasim::InputError naming `owner` (e.g. the camera's name) when sizes or focal
/// lengths are not positive, a value is not finite, or not 0 < near < far.
void validate(const PinholeIntrinsics& intrinsics, const std::string& owner);

/// OpenGL projection matrix (eye -> clip, see the file comment): z_eye = -near maps to depth -1,
/// z_eye = -far to +1, and pixel centres land on window pixel centres.
Eigen::Matrix4d projection_matrix(const PinholeIntrinsics& intrinsics);

/// GL view matrix (root -> GL eye) of a camera at `pose_root` (root <- camera, camera frame as
/// in the file comment).
Eigen::Matrix4d view_matrix(const Eigen::Isometry3d& pose_root);

/// A named camera: intrinsics and pose.
struct Camera {
  std::string name;  ///< appears in every error message about this camera
  PinholeIntrinsics intrinsics;
  Eigen::Isometry3d pose_root = Eigen::Isometry3d::Identity();  ///< root <- camera

  /// Point [m] from the root frame into the camera frame (x right, y down, z forward).
  Eigen::Vector3d to_camera(const Eigen::Vector3d& point_root) const {
    return pose_root.inverse(Eigen::Isometry) * point_root;
  }
  /// Pixel coordinates (u, v) of a root-frame point [m]; nullopt when the point is not in front
  /// of the optical centre (z <= 0 in the camera frame). The result may lie outside the image.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& point_root) const;
  /// projection_matrix(intrinsics) * view_matrix(pose_root): root -> clip.
  Eigen::Matrix4d view_projection() const;
};

}  // namespace somasim::render
