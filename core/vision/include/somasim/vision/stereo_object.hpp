#pragma once
/// @file
/// A round object seen by two posed cameras: its centre triangulated from the two images'
/// centres, its radius from their image radii and its depth (somasim/render/camera.hpp
/// conventions; points in the root frame [m]).
#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "somasim/render/camera.hpp"
#include "somasim/vision/stereo.hpp"

namespace somasim::vision {

struct StereoObject {
  Triangulation centre;  ///< the triangulated centre (valid, point [m], errors)
  /// Mean over both cameras of radius_px · z / f (z the centre's depth along each optical axis,
  /// f the mean focal length) [m]; 0 when the triangulation is not valid.
  double radius_m = 0.0;
  /// The larger over the smaller of the two cameras' radius_px · z / f (≥ 1): near 1 when both
  /// cameras see the same object, whatever its distance; 0 when the triangulation is not valid.
  double size_ratio = 0.0;
};

/// The object whose image centre is `uv_a` [px] with radius `radius_a_px` in camera `a`, and
/// `uv_b`, `radius_b_px` in `b`.
StereoObject triangulate_object(const render::Camera& a, const Eigen::Vector2d& uv_a,
                                double radius_a_px, const render::Camera& b,
                                const Eigen::Vector2d& uv_b, double radius_b_px);

/// Where a tracked object's image moves by its own motion: the translation (homogeneous 3 × 3,
/// u v 1, as ColourTracker::shift_window takes) of `camera`'s projection of
/// `position + velocity · dt_s` from that of `position` (root frame [m], [m/s], [s]). A search
/// window moved by it meets an object that moves farther in a frame than the window is wide
/// (fast or near objects). Identity when either point does not project (behind the camera).
cv::Matx33d predicted_image_shift(const render::Camera& camera, const Eigen::Vector3d& position,
                                  const Eigen::Vector3d& velocity, double dt_s);

}  // namespace somasim::vision
