#include "somasim/render/camera.hpp"

#include <fmt/format.h>

#include <cmath>

#include "somasim/error.hpp"

namespace somasim::render {

void validate(const PinholeIntrinsics& k, const std::string& owner) {
  if (k.width <= 0 || k.height <= 0)
    throw InputError(fmt::format("camera '{}': image size must be positive, got {} x {}", owner,
                                 k.width, k.height));
  for (const double v : {k.fx, k.fy, k.cx, k.cy, k.near, k.far})
    if (!std::isfinite(v))
      throw InputError(
          fmt::format("camera '{}': intrinsics must be finite (fx {}, fy {}, cx {}, "
                      "cy {}, near {}, far {})",
                      owner, k.fx, k.fy, k.cx, k.cy, k.near, k.far));
  if (k.fx <= 0.0 || k.fy <= 0.0)
    throw InputError(fmt::format("camera '{}': focal lengths must be positive, got fx {} fy {}",
                                 owner, k.fx, k.fy));
  if (!(k.near > 0.0 && k.near < k.far))
    throw InputError(fmt::format("camera '{}': clipping needs 0 < near < far, got near {} far {}",
                                 owner, k.near, k.far));
}

Eigen::Matrix4d projection_matrix(const PinholeIntrinsics& k) {
  // In the camera frame (x right, y down, z forward) the clip coordinates are
  //   x_clip = 2 fx / W x + (2 (cx + 0.5) / W - 1) z     (window x = u + 0.5, see camera.hpp)
  //   y_clip = 2 fy / H y + (2 (cy + 0.5) / H - 1) z     (window row = v: row 0 = image top)
  //   z_clip = A z + B, w_clip = z, with z_ndc = -1 at near and +1 at far.
  // The GL eye frame has y_eye = -y and z_eye = -z; the matrix below acts on eye coordinates.
  const double w = k.width, h = k.height, n = k.near, f = k.far;
  const double a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = 2.0 * k.fx / w;
  p(0, 2) = -(2.0 * (k.cx + 0.5) / w - 1.0);
  p(1, 1) = -2.0 * k.fy / h;
  p(1, 2) = -(2.0 * (k.cy + 0.5) / h - 1.0);
  p(2, 2) = -a;
  p(2, 3) = b;
  p(3, 2) = -1.0;
  return p;
}

Eigen::Matrix4d view_matrix(const Eigen::Isometry3d& pose_root) {
  Eigen::Matrix4d cv_to_gl = Eigen::Matrix4d::Identity();
  cv_to_gl(1, 1) = -1.0;
  cv_to_gl(2, 2) = -1.0;
  return cv_to_gl * pose_root.inverse(Eigen::Isometry).matrix();
}

std::optional<Eigen::Vector2d> Camera::project(const Eigen::Vector3d& point_root) const {
  const Eigen::Vector3d p = to_camera(point_root);
  if (!(p.z() > 0.0)) return std::nullopt;
  return Eigen::Vector2d(intrinsics.fx * p.x() / p.z() + intrinsics.cx,
                         intrinsics.fy * p.y() / p.z() + intrinsics.cy);
}

Eigen::Matrix4d Camera::view_projection() const {
  return projection_matrix(intrinsics) * view_matrix(pose_root);
}

}  // namespace somasim::render
