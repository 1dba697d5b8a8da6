#include "somasim/vision/stereo_object.hpp"

#include <algorithm>

namespace somasim::vision {
namespace {

double metric_radius(const render::Camera& camera, const Eigen::Vector3d& point_root,
                     double radius_px) {
  const double z = camera.to_camera(point_root).z();
  const double f = 0.5 * (camera.intrinsics.fx + camera.intrinsics.fy);
  return radius_px * z / f;
}

}  // namespace

StereoObject triangulate_object(const render::Camera& a, const Eigen::Vector2d& uv_a,
                                double radius_a_px, const render::Camera& b,
                                const Eigen::Vector2d& uv_b, double radius_b_px) {
  StereoObject out;
  out.centre = triangulate(a, uv_a, b, uv_b);
  if (!out.centre.valid) return out;
  const double in_a = metric_radius(a, out.centre.point, radius_a_px);
  const double in_b = metric_radius(b, out.centre.point, radius_b_px);
  out.radius_m = 0.5 * (in_a + in_b);
  const double smaller = std::min(in_a, in_b);
  out.size_ratio = smaller > 0.0 ? std::max(in_a, in_b) / smaller : 0.0;
  return out;
}

cv::Matx33d predicted_image_shift(const render::Camera& camera, const Eigen::Vector3d& position,
                                  const Eigen::Vector3d& velocity, double dt_s) {
  const auto now = camera.project(position);
  const auto next = camera.project(position + velocity * dt_s);
  if (!now || !next) return cv::Matx33d::eye();
  const Eigen::Vector2d d = *next - *now;
  return {1.0, 0.0, d.x(), 0.0, 1.0, d.y(), 0.0, 0.0, 1.0};
}

}  // namespace somasim::vision
