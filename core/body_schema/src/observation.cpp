#include "somasim/body_schema/observation.hpp"

#include <opencv2/imgproc.hpp>

namespace somasim::body_schema {

cv::Mat segment_colour(const cv::Mat& rgb, const HsvRange& range) {
  CV_Assert(rgb.type() == CV_8UC3);
  cv::Mat hsv, mask;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  cv::inRange(hsv, range.low, range.high, mask);
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  return mask;
}

cv::Mat canny_edges(const cv::Mat& rgb, double canny_low, double canny_high,
                    cv::Mat* blurred_grey) {
  CV_Assert(rgb.type() == CV_8UC3);
  cv::Mat grey, edges;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  cv::blur(grey, grey, {3, 3});
  cv::Canny(grey, edges, canny_low, canny_high);
  if (blurred_grey) *blurred_grey = grey;
  return edges;
}

cv::Mat edge_distance_map(const cv::Mat& rgb, double canny_low, double canny_high) {
  const cv::Mat edges = canny_edges(rgb, canny_low, canny_high);
  cv::Mat distance, out;
  // distanceTransform measures the distance to the nearest zero pixel: edges become zeros.
  cv::distanceTransform(255 - edges, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  distance.convertTo(out, CV_8U);  // rounds and saturates at 255
  return out;
}

}  // namespace somasim::body_schema
