#pragma once
/// @file
/// Oriented chamfer matching of a hypothesis's contour against the observed edges: besides how
/// far each contour pixel is from the nearest observed edge, whether that edge runs the same
/// way. On a cluttered image the plain chamfer distance of a hand's outer contour changes
/// little as the hand turns (some edge of the clutter is always near); the direction of the
/// nearest edge does. Orientations are those of edge normals, in degrees mod 180, in image
/// coordinates (x right, y down).
#include <opencv2/core.hpp>

namespace somasim::body_schema {

/// The observation of one camera for the oriented edge likelihood (CV_8UC2, image size):
/// channel 0 the distance to the nearest Canny edge [px] as edge_distance_map (grey, 3×3 blur,
/// Canny(low, high), saturated at 255; L2 through a 5×5 mask, which can label the nearest edge);
/// channel 1 the normal orientation of that nearest edge [deg, 0..179]: the dominant direction of
/// the blurred grey image's structure tensor there (gradients over a 7×7 Gaussian window).
cv::Mat oriented_edge_map(const cv::Mat& rgb, double canny_low = 65.0, double canny_high = 195.0);

/// The normal orientation [deg, 0..179] at each pixel of a thin contour tile (CV_8U, non-zero on
/// the contour; the result CV_8U, 0 off it): the dominant direction of the structure tensor of
/// the tile's gradients over a 7×7 Gaussian window (a 1-2 px line has opposite gradients on its
/// two sides; their tensor agrees).
cv::Mat contour_normal_orientation(const cv::Mat& contour_tile);

/// Mean over the contour pixels of d + weight·Δθ/90°: d the distance to the nearest observed
/// edge [px], Δθ [deg, 0..90] the angle between the contour's normal and that edge's normal;
/// `oriented_roi` (CV_8UC2, oriented_edge_map cut to the tile's ROI), `contour_tile` (CV_8U, the
/// same size), `weight_px` [px] the cost of a perpendicular edge. 255 + weight_px when the
/// contour is empty.
double mean_oriented_chamfer_distance(const cv::Mat& oriented_roi, const cv::Mat& contour_tile,
                                      double weight_px);

}  // namespace somasim::body_schema
