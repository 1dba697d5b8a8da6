#pragma once
/// @file
/// A round object seen by two posed cameras: its centre triangulated from the two images'
/// centres, its radius from their image radii and its depth (somasim/render/camera.hpp
/// conventions; points in the root frame [m]).
#include <Eigen/Core>

#include "somasim/render/camera.hpp"
#include "somasim/vision/stereo.hpp"

namespace somasim::vision {

struct StereoObject {
  Triangulation centre;  ///< the triangulated centre (valid, point [m], errors)
  /// Mean over both cameras of radius_px · z / f (z the centre's depth along each optical axis,
  /// f the mean focal length) [m]; 0 when the triangulation is not valid.
  double radius_m = 0.0;
};

/// The object whose image centre is `uv_a` [px] with radius `radius_a_px` in camera `a`, and
/// `uv_b`, `radius_b_px` in `b`.
StereoObject triangulate_object(const render::Camera& a, const Eigen::Vector2d& uv_a,
                                double radius_a_px, const render::Camera& b,
                                const Eigen::Vector2d& uv_b, double radius_b_px);

}  // namespace somasim::vision
