#pragma once
/// @file
/// What the robot computes from its camera images to compare them with its mental images
/// (Vicente et al. 2016, section 3.4), as a robot would: from the RGB pixels only.
///
/// Images are cv::Mat CV_8UC3 in R, G, B channel order (somasim::render's Image encoding).
#include <opencv2/core.hpp>

namespace somasim::body_schema {

/// A box in HSV space (OpenCV 8-bit convention: hue 0–179, saturation and value 0–255).
struct HsvRange {
  cv::Scalar low{0, 40, 60};
  cv::Scalar high{30, 255, 255};
};

/// Silhouette by colour segmentation: 255 where the pixel's HSV lies in `range`, else 0, then a
/// 3×3 morphological opening removes isolated pixels (CV_8U, the image's size).
cv::Mat segment_colour(const cv::Mat& rgb, const HsvRange& range);

/// The released code's edges: grey → 3×3 blur → Canny(low, high) (CV_8U, 255 on edges); the
/// blurred grey image in `*blurred_grey` when given.
cv::Mat canny_edges(const cv::Mat& rgb, double canny_low, double canny_high,
                    cv::Mat* blurred_grey = nullptr);

/// Edge observation (the released code): grey → 3×3 blur → Canny(low, high) → L2 distance
/// transform to the nearest edge pixel [px], saturated to 8 bits (CV_8U, 0 on edges, ≤ 255).
cv::Mat edge_distance_map(const cv::Mat& rgb, double canny_low = 65.0, double canny_high = 195.0);

}  // namespace somasim::body_schema
