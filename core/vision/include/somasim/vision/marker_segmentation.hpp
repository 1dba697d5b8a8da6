#pragma once
/// @file
/// Colour-marker segmentation: the largest blob of pixels whose HSV colour lies in a range.
///
/// Images are rgb8 (CV_8UC3, channels R, G, B; pixel conventions of somasim/render/camera.hpp:
/// the centre of pixel (column c, row r) is at (u, v) = (c, r)). HSV values follow OpenCV's 8-bit
/// convention: hue in [0, 179] (degrees / 2: red 0, yellow 30, green 60, blue 120), saturation
/// and value in [0, 255].
#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include <Eigen/Core>

namespace somasim::vision {

/// An inclusive HSV box. When low.h > high.h the hue range wraps around 180 (e.g. red: 170..10).
struct HsvRange {
  cv::Vec3b low{45, 80, 40};     ///< h, s, v (default: green)
  cv::Vec3b high{75, 255, 255};  ///< h, s, v
};

/// A connected blob (8-connectivity) of in-range pixels.
struct MarkerBlob {
  bool found = false;  ///< a blob of at least min_area_px pixels exists
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();  ///< (u, v) of its pixel centres [px]
  /// The smallest circle around its pixel centres [px]: for a round marker partly hidden (up to
  /// half of it, e.g. behind the finger it sits on) a better estimate of the marker's centre
  /// than the centroid, which moves toward the visible part.
  Eigen::Vector2d circle_centre_px = Eigen::Vector2d::Zero();
  double circle_radius_px = 0.0;
  int area_px = 0;     ///< its pixels (0 when nothing matched)
  int matched_px = 0;  ///< all in-range pixels of the image, in every blob
};

/// Segments `rgb` (CV_8UC3, R G B) by `range` and returns its largest blob; found only when that
/// blob has at least `min_area_px` pixels (>= 1). Throws somasim::InputError "segment_marker:
/// expected an rgb8 image (CV_8UC3), got <type>" for another image type or an empty image, and
/// "segment_marker: min_area_px: expected >= 1, got N".
MarkerBlob segment_marker(const cv::Mat& rgb, const HsvRange& range, int min_area_px = 1);

/// All blobs of at least `min_area_px` pixels, largest first, at most `max_blobs` of them (each
/// with matched_px = all in-range pixels of the image). Errors as segment_marker.
std::vector<MarkerBlob> segment_blobs(const cv::Mat& rgb, const HsvRange& range, int min_area_px,
                                      std::size_t max_blobs);

/// The in-range mask (CV_8U, 255 where the pixel's HSV colour is in `range`) of an rgb8 image.
cv::Mat hsv_mask(const cv::Mat& rgb, const HsvRange& range);

}  // namespace somasim::vision
