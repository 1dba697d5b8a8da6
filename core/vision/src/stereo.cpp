#include "somasim/vision/stereo.hpp"

#include <cmath>

namespace somasim::vision {

Ray pixel_ray(const render::Camera& camera, const Eigen::Vector2d& uv) {
  const render::PinholeIntrinsics& k = camera.intrinsics;
  const Eigen::Vector3d in_camera((uv.x() - k.cx) / k.fx, (uv.y() - k.cy) / k.fy, 1.0);
  Ray ray;
  ray.origin = camera.pose_root.translation();
  ray.direction = (camera.pose_root.linear() * in_camera).normalized();
  return ray;
}

Triangulation triangulate(const render::Camera& a, const Eigen::Vector2d& uv_a,
                          const render::Camera& b, const Eigen::Vector2d& uv_b) {
  const Ray ra = pixel_ray(a, uv_a);
  const Ray rb = pixel_ray(b, uv_b);
  // Closest points ra.origin + s da and rb.origin + t db: (w0 + s da - t db) ⊥ da, db.
  const Eigen::Vector3d w0 = ra.origin - rb.origin;
  const double ab = ra.direction.dot(rb.direction);
  const double denom = 1.0 - ab * ab;  // unit directions
  Triangulation out;
  if (denom < 1e-12) return out;  // parallel rays: no depth
  const double d = ra.direction.dot(w0), e = rb.direction.dot(w0);
  const double s = (ab * e - d) / denom;
  const double t = (e - ab * d) / denom;
  if (s <= 0.0 || t <= 0.0) return out;  // behind a camera
  const Eigen::Vector3d pa = ra.origin + s * ra.direction;
  const Eigen::Vector3d pb = rb.origin + t * rb.direction;
  out.point = 0.5 * (pa + pb);
  out.ray_gap_m = (pa - pb).norm();
  const auto err = [&](const render::Camera& c, const Eigen::Vector2d& uv) {
    const auto p = c.project(out.point);
    return p ? (*p - uv).squaredNorm() : INFINITY;
  };
  out.reprojection_error_px = std::sqrt(0.5 * (err(a, uv_a) + err(b, uv_b)));
  out.valid = std::isfinite(out.reprojection_error_px);
  return out;
}

}  // namespace somasim::vision
