#pragma once
// A synthetic stereo scene for the vision tests: two iCub-like eyes (320 × 240 px, 68 mm apart,
// verged on a point 0.4 m ahead along root +x), a textured backdrop of grey and random
// rectangles (no saturated red), and a sphere drawn as a red disc of its projected radius.
#include <cmath>

#include <Eigen/Core>
#include <opencv2/imgproc.hpp>

#include "somasim/render/camera.hpp"

namespace somasim::vision::test {

/// The eye at lateral offset `y` [m] (root frame, 0.3 m up), looking at (0.4, 0, 0.25).
inline render::Camera eye(double y) {
  render::Camera c;
  c.intrinsics = {320, 240, 257.34, 257.34, 159.5, 119.5, 0.04, 100};
  const Eigen::Vector3d origin(0, y, 0.3), target(0.4, 0, 0.25);
  const Eigen::Vector3d z = (target - origin).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  c.pose_root.linear() << x, z.cross(x), z;
  c.pose_root.translation() = origin;
  return c;
}

inline const render::Camera kLeftEye = eye(0.034);
inline const render::Camera kRightEye = eye(-0.034);

/// 50 rectangles of random hue (25-155: no red), saturation and value on grey, rgb8 320 × 240.
inline cv::Mat backdrop() {
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar(110, 110, 110));
  cv::RNG rng(11);
  for (int i = 0; i < 50; ++i) {
    // One draw per statement: the order of evaluation of function arguments is unspecified.
    const int hue = rng.uniform(25, 155);
    const int saturation = rng.uniform(0, 255);
    const int value = rng.uniform(40, 255);
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue, saturation, value));
    cv::Mat rgb;
    cv::cvtColor(hsv, rgb, cv::COLOR_HSV2RGB);
    const int x = rng.uniform(0, 320);
    const int y = rng.uniform(0, 240);
    const int w = rng.uniform(8, 50);
    const int h = rng.uniform(8, 50);
    cv::rectangle(image, cv::Rect(x, y, w, h), cv::Scalar(rgb.at<cv::Vec3b>(0, 0)), cv::FILLED);
  }
  return image;
}

/// The red of the spheres (rgb8).
inline const cv::Scalar kSphereRgb(210, 35, 30);

/// `bg` with the sphere (centre p [m], radius r [m]) as camera `c` sees it: a disc of radius
/// f r / z.
inline cv::Mat view(const cv::Mat& bg, const render::Camera& c, const Eigen::Vector3d& p,
                    double r) {
  cv::Mat image = bg.clone();
  const Eigen::Vector2d uv = *c.project(p);
  const double radius_px = c.intrinsics.fx * r / c.to_camera(p).z();
  cv::circle(image,
             cv::Point(static_cast<int>(std::lround(uv.x() * 16)),
                       static_cast<int>(std::lround(uv.y() * 16))),
             static_cast<int>(std::lround(radius_px * 16)), kSphereRgb, cv::FILLED, cv::LINE_AA, 4);
  return image;
}

}  // namespace somasim::vision::test
