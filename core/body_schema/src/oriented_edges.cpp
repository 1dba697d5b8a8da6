#include "somasim/body_schema/oriented_edges.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "somasim/body_schema/observation.hpp"

namespace somasim::body_schema {

namespace {

// Half the angle of the vector (a, b) [deg], mod 180, rounded: 0..179.
std::uint8_t half_angle_deg(double a, double b) {
  const double deg = 0.5 * std::atan2(b, a) * 180.0 / std::numbers::pi;  // -90..90
  return static_cast<std::uint8_t>((std::lround(deg) + 180) % 180);
}

// Normal orientation [deg, 0..179] at the non-zero pixels of `where` (CV_8U, the size of
// `image`; 0 elsewhere) of `image` (CV_8U): the dominant direction of the structure tensor of
// its gradients (after a 5x5 Gaussian blur, sigma 1 px) over a Gaussian window (7x7, sigma
// 1.5 px), which averages out the staircase of aliased edges and agrees on both sides of a thin
// line.
cv::Mat normal_orientations(const cv::Mat& image, const cv::Mat& where) {
  cv::Mat smooth, gx, gy;
  cv::GaussianBlur(image, smooth, {5, 5}, 1.0);
  cv::Sobel(smooth, gx, CV_32F, 1, 0, 3);
  cv::Sobel(smooth, gy, CV_32F, 0, 1, 3);
  cv::Mat gxx = gx.mul(gx), gyy = gy.mul(gy), gxy = gx.mul(gy);
  for (cv::Mat* m : {&gxx, &gyy, &gxy}) cv::GaussianBlur(*m, *m, {7, 7}, 1.5);
  cv::Mat out = cv::Mat::zeros(image.size(), CV_8U);
  for (int r = 0; r < out.rows; ++r) {
    const std::uint8_t* w = where.ptr<std::uint8_t>(r);
    for (int c = 0; c < out.cols; ++c) {
      if (w[c] == 0) continue;
      // The tensor's dominant eigenvector is at half the angle of (gxx - gyy, 2 gxy).
      const double a = gxx.at<float>(r, c) - gyy.at<float>(r, c), b = 2.0 * gxy.at<float>(r, c);
      out.at<std::uint8_t>(r, c) = half_angle_deg(a, b);
    }
  }
  return out;
}

}  // namespace

cv::Mat oriented_edge_map(const cv::Mat& rgb, double canny_low, double canny_high) {
  cv::Mat grey, distance, labels;
  const cv::Mat edges = canny_edges(rgb, canny_low, canny_high, &grey);
  const cv::Mat normals = normal_orientations(grey, edges);
  // Labels number the zero pixels (the edges) of the input in row-major order.
  cv::distanceTransform(255 - edges, distance, labels, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  std::vector<std::uint8_t> edge_orientation(1, 0);  // label 0: no edge at all
  for (int r = 0; r < edges.rows; ++r)
    for (int c = 0; c < edges.cols; ++c)
      if (edges.at<std::uint8_t>(r, c) != 0)
        edge_orientation.push_back(normals.at<std::uint8_t>(r, c));
  cv::Mat out(rgb.size(), CV_8UC2);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const auto label = static_cast<std::size_t>(labels.at<int>(r, c));
      const float d = distance.at<float>(r, c);
      out.at<cv::Vec2b>(r, c) =
          cv::Vec2b(static_cast<std::uint8_t>(std::min(255L, std::lround(d))),
                    label < edge_orientation.size() ? edge_orientation[label] : std::uint8_t{0});
    }
  return out;
}

cv::Mat contour_normal_orientation(const cv::Mat& contour_tile) {
  CV_Assert(contour_tile.type() == CV_8U);
  return normal_orientations(contour_tile, contour_tile);
}

double mean_oriented_chamfer_distance(const cv::Mat& oriented_roi, const cv::Mat& contour_tile,
                                      double weight_px) {
  CV_Assert(oriented_roi.type() == CV_8UC2 && contour_tile.type() == CV_8U &&
            oriented_roi.size() == contour_tile.size());
  const cv::Mat normal = contour_normal_orientation(contour_tile);
  double sum = 0.0;
  std::int64_t count = 0;
  for (int r = 0; r < contour_tile.rows; ++r) {
    const cv::Vec2b* o = oriented_roi.ptr<cv::Vec2b>(r);
    const std::uint8_t* e = contour_tile.ptr<std::uint8_t>(r);
    const std::uint8_t* n = normal.ptr<std::uint8_t>(r);
    for (int c = 0; c < contour_tile.cols; ++c) {
      if (e[c] == 0) continue;
      int dtheta = std::abs(static_cast<int>(n[c]) - static_cast<int>(o[c][1]));
      if (dtheta > 90) dtheta = 180 - dtheta;
      sum += o[c][0] + weight_px * dtheta / 90.0;
      ++count;
    }
  }
  return count == 0 ? 255.0 + weight_px : sum / static_cast<double>(count);
}

}  // namespace somasim::body_schema
