#include "somasim/vision/motion_detection.hpp"

#include <string>
#include <vector>

#include <Eigen/Dense>

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "somasim/error.hpp"

namespace somasim::vision {
namespace {

std::string describe(const cv::Mat& m) {
  if (m.empty()) return "an empty image";
  return fmt::format("{} {} × {}", cv::typeToString(m.type()), m.cols, m.rows);
}

void check_pair(const cv::Mat& previous, const cv::Mat& current) {
  if (previous.empty() || current.empty() || previous.type() != CV_8UC3 ||
      current.type() != CV_8UC3 || previous.size() != current.size())
    throw InputError(
        fmt::format("detect_motion: expected two rgb8 images (CV_8UC3) of one size, got {} and {}",
                    describe(previous), describe(current)));
}

cv::Mat disc(int radius_px) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                   cv::Size(2 * radius_px + 1, 2 * radius_px + 1));
}

}  // namespace

cv::Mat dense_flow(const cv::Mat& previous, const cv::Mat& current) {
  check_pair(previous, current);
  cv::Mat a, b, flow;
  cv::cvtColor(previous, a, cv::COLOR_RGB2GRAY);
  cv::cvtColor(current, b, cv::COLOR_RGB2GRAY);
  // Three pyramid levels (moves of up to ~20 px), 15 px windows, 5 px polynomial neighbourhood.
  cv::calcOpticalFlowFarneback(a, b, flow, 0.5, 3, 15, 3, 5, 1.2, 0);
  return flow;
}

cv::Matx33d rotation_homography(const Eigen::Matrix3d& previous_root,
                                const Eigen::Matrix3d& current_root, double fx, double fy,
                                double cx, double cy) {
  const Eigen::Matrix3d r = current_root.transpose() * previous_root;
  Eigen::Matrix3d k;
  k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  const Eigen::Matrix3d h = k * r * k.inverse();
  cv::Matx33d out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out(i, j) = h(i, j);
  return out;
}

MotionBlob detect_motion(const cv::Mat& previous, const cv::Mat& current,
                         const MotionOptions& options, const cv::Matx33d& previous_to_current) {
  if (options.min_area_px < 1)
    throw InputError(
        fmt::format("detect_motion: min_area_px: expected >= 1, got {}", options.min_area_px));
  check_pair(previous, current);
  cv::Mat valid;  // pixels of the current image that the previous one saw (ego-motion only)
  cv::Mat flow;
  if (previous_to_current == cv::Matx33d::eye()) {
    flow = dense_flow(previous, current);
  } else {
    cv::Mat warped;
    cv::warpPerspective(previous, warped, previous_to_current, previous.size(), cv::INTER_LINEAR,
                        cv::BORDER_REPLICATE);
    cv::warpPerspective(cv::Mat(previous.size(), CV_8U, cv::Scalar(255)), valid,
                        previous_to_current, previous.size(), cv::INTER_NEAREST,
                        cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::erode(valid, valid, disc(2));
    flow = dense_flow(warped, current);
  }
  std::vector<cv::Mat> uv;
  cv::split(flow, uv);
  cv::Mat magnitude;
  cv::magnitude(uv[0], uv[1], magnitude);
  cv::Mat mask = magnitude > options.min_flow_px;
  if (!valid.empty()) mask &= valid;
  if (options.open_radius_px > 0)
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, disc(options.open_radius_px));
  if (options.close_radius_px > 0)
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, disc(options.close_radius_px));

  MotionBlob blob;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0, best_area = 0;
  for (int i = 1; i < n; ++i) {  // label 0 is the still background; ties: the first label
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area > best_area) best = i, best_area = area;
  }
  if (best == 0 || best_area < options.min_area_px) return blob;
  blob.found = true;
  blob.area_px = best_area;
  blob.box =
      cv::Rect(stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
               stats.at<int>(best, cv::CC_STAT_WIDTH), stats.at<int>(best, cv::CC_STAT_HEIGHT));
  blob.centroid_px = {centroids.at<double>(best, 0), centroids.at<double>(best, 1)};
  blob.mask = labels == best;
  const cv::Scalar mean_flow = cv::mean(flow, blob.mask);
  blob.mean_flow_px = {mean_flow[0], mean_flow[1]};
  return blob;
}

}  // namespace somasim::vision
