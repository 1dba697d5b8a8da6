#include "somasim/vision/marker_segmentation.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"

namespace somasim::vision {

cv::Mat hsv_mask(const cv::Mat& rgb, const HsvRange& range) {
  if (rgb.empty() || rgb.type() != CV_8UC3)
    throw InputError(
        fmt::format("segment_marker: expected an rgb8 image (CV_8UC3), got {}",
                    rgb.empty() ? std::string("an empty image") : cv::typeToString(rgb.type())));
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  const cv::Vec3b& lo = range.low;
  const cv::Vec3b& hi = range.high;
  cv::Mat mask;
  if (lo[0] <= hi[0]) {
    cv::inRange(hsv, cv::Scalar(lo[0], lo[1], lo[2]), cv::Scalar(hi[0], hi[1], hi[2]), mask);
  } else {  // hue wraps around 180
    cv::Mat upper;
    cv::inRange(hsv, cv::Scalar(lo[0], lo[1], lo[2]), cv::Scalar(179, hi[1], hi[2]), mask);
    cv::inRange(hsv, cv::Scalar(0, lo[1], lo[2]), cv::Scalar(hi[0], hi[1], hi[2]), upper);
    mask |= upper;
  }
  return mask;
}

namespace {

void check_min_area(int min_area_px) {
  if (min_area_px < 1)
    throw InputError(
        fmt::format("segment_marker: min_area_px: expected >= 1, got {}", min_area_px));
}

// Every blob of the mask with its area, centroid and enclosing circle, largest first; only
// blobs of at least `min_area_px` unless `keep_largest` (then also the largest, whatever its size).
std::vector<MarkerBlob> blobs_of(const cv::Mat& mask, int min_area_px, std::size_t max_blobs,
                                 bool keep_largest) {
  std::vector<MarkerBlob> out;
  const int matched = cv::countNonZero(mask);
  if (matched == 0) return out;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<int> order;
  for (int i = 1; i < n; ++i) order.push_back(i);  // label 0 is the background
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return stats.at<int>(a, cv::CC_STAT_AREA) > stats.at<int>(b, cv::CC_STAT_AREA);
  });
  for (const int label : order) {
    if (out.size() >= max_blobs) break;
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < min_area_px && !(keep_largest && out.empty())) break;
    MarkerBlob blob;
    blob.matched_px = matched;
    blob.area_px = area;
    blob.centroid_px = {centroids.at<double>(label, 0), centroids.at<double>(label, 1)};
    std::vector<cv::Point> points;
    cv::findNonZero(labels == label, points);
    cv::Point2f centre;
    float radius = 0.f;
    cv::minEnclosingCircle(points, centre, radius);
    blob.circle_centre_px = {centre.x, centre.y};
    blob.circle_radius_px = radius;
    blob.found = area >= min_area_px;
    out.push_back(blob);
  }
  return out;
}

}  // namespace

MarkerBlob segment_marker(const cv::Mat& rgb, const HsvRange& range, int min_area_px) {
  check_min_area(min_area_px);
  const cv::Mat mask = hsv_mask(rgb, range);
  const std::vector<MarkerBlob> blobs = blobs_of(mask, min_area_px, 1, true);
  if (!blobs.empty()) return blobs.front();
  return {};
}

std::vector<MarkerBlob> segment_blobs(const cv::Mat& rgb, const HsvRange& range, int min_area_px,
                                      std::size_t max_blobs) {
  check_min_area(min_area_px);
  return blobs_of(hsv_mask(rgb, range), min_area_px, max_blobs, false);
}

}  // namespace somasim::vision
