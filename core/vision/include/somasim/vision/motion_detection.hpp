#pragma once
/// @file
/// Motion detection by dense optical flow: the largest region of an image that moved between two
/// consecutive frames of one camera (cv::calcOpticalFlowFarneback).
///
/// Images are rgb8 (CV_8UC3, R G B; pixel conventions of somasim/render/camera.hpp). Flow is in
/// pixels per frame. A turning head moves the whole image: pass the homography that maps the
/// previous image's pixels to the current one's for the camera's own rotation (see
/// rotation_homography; the translation of the eyes is neglected, a parallax of baseline /
/// depth), and the previous image is warped by it before the flow (pixels that have no
/// counterpart in the previous image never count as moving).
#include <opencv2/core.hpp>

#include <Eigen/Core>

namespace somasim::vision {

struct MotionOptions {
  double min_flow_px = 0.5;  ///< flow magnitude that counts as motion [px/frame]
  int open_radius_px = 1;    ///< morphological opening (removes specks) [px]; 0: none
  int close_radius_px = 3;   ///< morphological closing (fills the blob) [px]; 0: none
  int min_area_px = 20;      ///< smallest moving blob [px]
};

/// The largest 8-connected moving region.
struct MotionBlob {
  bool found = false;  ///< a moving blob of at least min_area_px pixels exists
  cv::Rect box;        ///< its bounding box [px]
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();   ///< (u, v) [px]
  int area_px = 0;                                         ///< its pixels
  Eigen::Vector2d mean_flow_px = Eigen::Vector2d::Zero();  ///< its mean flow [px/frame]
  cv::Mat mask;  ///< CV_8U, image size, 255 on the blob (empty when not found)
};

/// The largest region that moved from `previous` to `current` (both rgb8 of one size). Throws
/// somasim::InputError "detect_motion: expected two rgb8 images (CV_8UC3) of one size, got
/// <type> W × H and <type> W × H" otherwise, and "detect_motion: min_area_px: expected >= 1,
/// got N".
/// `previous_to_current` maps previous pixels to current ones (homogeneous, u v 1) for the
/// camera's ego-motion; identity for a still camera.
MotionBlob detect_motion(const cv::Mat& previous, const cv::Mat& current,
                         const MotionOptions& options = {},
                         const cv::Matx33d& previous_to_current = cv::Matx33d::eye());

/// The homography K R_currentᵀ R_previous K⁻¹ of a camera that rotated from `previous_root`
/// to `current_root` (root <- camera rotations) with intrinsics fx, fy, cx, cy [px].
cv::Matx33d rotation_homography(const Eigen::Matrix3d& previous_root,
                                const Eigen::Matrix3d& current_root, double fx, double fy,
                                double cx, double cy);

/// The dense flow (CV_32FC2, [px/frame]) from `previous` to `current` (rgb8, one size); same
/// errors as detect_motion.
cv::Mat dense_flow(const cv::Mat& previous, const cv::Mat& current);

}  // namespace somasim::vision
