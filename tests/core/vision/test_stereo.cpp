// Stereo triangulation with synthetic pinhole cameras: exact points from exact pixels, rays
// that miss each other, parallel rays and points behind a camera.
#include <gtest/gtest.h>

#include <random>

#include "somasim/vision/stereo.hpp"

namespace render = somasim::render;
namespace vision = somasim::vision;

namespace {

// Two iCub-like eyes 68 mm apart, verged on a point 0.35 m ahead, looking along root +x.
render::Camera eye(double y, const char* name) {
  render::Camera c;
  c.name = name;
  c.intrinsics = {320, 240, 257.34, 257.34, 160, 120, 0.04, 100};
  const Eigen::Vector3d origin(0, y, 0.3);
  const Eigen::Vector3d target(0.35, 0, 0.25);
  const Eigen::Vector3d z = (target - origin).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();  // image right
  const Eigen::Vector3d y_axis = z.cross(x);                                 // image down
  c.pose_root.linear() << x, y_axis, z;
  c.pose_root.translation() = origin;
  return c;
}

const render::Camera kLeft = eye(0.034, "left_eye");  // root y to the left
const render::Camera kRight = eye(-0.034, "right_eye");

}  // namespace

TEST(Stereo, PixelRayPassesThroughTheProjectedPoint) {
  const Eigen::Vector3d p(0.3, 0.05, 0.2);
  const vision::Ray ray = vision::pixel_ray(kLeft, *kLeft.project(p));
  EXPECT_NEAR(ray.direction.norm(), 1.0, 1e-12);
  EXPECT_LT((ray.origin + (p - ray.origin).norm() * ray.direction - p).norm(), 1e-12);
}

TEST(Stereo, ExactPixelsGiveThePointWithinAMicrometre) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p(0.35 + 1.5 * u(rng), u(rng), 0.25 + u(rng));
    const vision::Triangulation t =
        vision::triangulate(kLeft, *kLeft.project(p), kRight, *kRight.project(p));
    ASSERT_TRUE(t.valid) << p.transpose();
    EXPECT_LT((t.point - p).norm(), 1e-6) << p.transpose();
    EXPECT_LT(t.ray_gap_m, 1e-9);
    EXPECT_LT(t.reprojection_error_px, 1e-6);
  }
}

TEST(Stereo, RaysThatMissGiveTheMidpointAndTheirGap) {
  const Eigen::Vector3d p(0.35, 0.02, 0.22);
  // Shift the right eye's pixel vertically: the rays no longer meet.
  const Eigen::Vector2d left = *kLeft.project(p);
  const Eigen::Vector2d right = *kRight.project(p) + Eigen::Vector2d(0, 3);
  const vision::Triangulation t = vision::triangulate(kLeft, left, kRight, right);
  ASSERT_TRUE(t.valid);
  // The midpoint of the common perpendicular: equidistant from both rays, gap between them.
  const vision::Ray ra = vision::pixel_ray(kLeft, left), rb = vision::pixel_ray(kRight, right);
  const auto distance = [&](const vision::Ray& r) {
    return (t.point - r.origin).cross(r.direction).norm();
  };
  EXPECT_NEAR(distance(ra), 0.5 * t.ray_gap_m, 1e-9);
  EXPECT_NEAR(distance(rb), 0.5 * t.ray_gap_m, 1e-9);
  // 3 px at about 0.35 m and f = 257 px: about 4 mm apart.
  EXPECT_GT(t.ray_gap_m, 0.002);
  EXPECT_LT(t.ray_gap_m, 0.006);
  EXPECT_GT(t.reprojection_error_px, 1.0);
  EXPECT_LT(t.reprojection_error_px, 2.0);
  EXPECT_LT((t.point - p).norm(), 0.005);
}

TEST(Stereo, ParallelRaysOrAPointBehindAreInvalid) {
  // The same pixel in two cameras with parallel axes: parallel rays, no depth.
  render::Camera a = kLeft, b = kLeft;
  b.pose_root.translation().y() += 0.068;
  EXPECT_FALSE(vision::triangulate(a, {160, 120}, b, {160, 120}).valid);
  // Rays that diverge: their closest points lie behind the cameras.
  EXPECT_FALSE(vision::triangulate(kLeft, {10, 120}, kRight, {310, 120}).valid);
}
