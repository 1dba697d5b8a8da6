// Oriented chamfer matching: the observed edges' normal orientations (nearest edge per pixel),
// a thin contour's normal orientation, and the cost that adds the angle between them — generated
// lines at every orientation, and a contour turned against the edges it lies on.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "somasim/body_schema/observation.hpp"
#include "somasim/body_schema/oriented_edges.hpp"

namespace somasim::body_schema {
namespace {

// Angle between two orientations mod 180 [deg, 0..90].
int angle_between(int a, int b) {
  const int d = std::abs(a - b) % 180;
  return d > 90 ? 180 - d : d;
}

// A 1 px line through (80, 60) whose normal points at `normal_deg` (image x right, y down).
cv::Mat line_tile(double normal_deg, int width = 1) {
  cv::Mat tile = cv::Mat::zeros(120, 160, CV_8U);
  const double a = normal_deg * std::numbers::pi / 180.0;
  const cv::Point2d along(-std::sin(a), std::cos(a));
  cv::line(tile, cv::Point2d(80, 60) - 50.0 * along, cv::Point2d(80, 60) + 50.0 * along,
           cv::Scalar(255), width);
  return tile;
}

// A white image with a black filled half-plane whose border has normal `normal_deg`.
cv::Mat half_plane(double normal_deg) {
  cv::Mat rgb(120, 160, CV_8UC3, cv::Scalar(255, 255, 255));
  const double a = normal_deg * std::numbers::pi / 180.0;
  for (int r = 0; r < rgb.rows; ++r)
    for (int c = 0; c < rgb.cols; ++c)
      if ((c - 80) * std::cos(a) + (r - 60) * std::sin(a) > 0)
        rgb.at<cv::Vec3b>(r, c) = cv::Vec3b(0, 0, 0);
  return rgb;
}

TEST(OrientedEdges, AContoursNormalIsFoundAtEveryOrientation) {
  for (int deg = 0; deg < 180; deg += 7) {
    for (const int width : {1, 2}) {
      const cv::Mat tile = line_tile(deg, width);
      const cv::Mat normal = contour_normal_orientation(tile);
      // Away from the line's ends, every contour pixel's normal is within 8 deg.
      const cv::Mat centre = tile(cv::Rect(60, 40, 40, 40));
      int worst = 0;
      for (int r = 0; r < centre.rows; ++r)
        for (int c = 0; c < centre.cols; ++c)
          if (centre.at<std::uint8_t>(r, c))
            worst = std::max(worst, angle_between(normal.at<std::uint8_t>(40 + r, 60 + c), deg));
      EXPECT_LE(worst, 8) << deg << " deg, width " << width;
    }
  }
}

TEST(OrientedEdges, EachPixelCarriesTheNearestObservedEdgesNormal) {
  for (int deg = 0; deg < 180; deg += 11) {
    const cv::Mat map = oriented_edge_map(half_plane(deg));
    ASSERT_EQ(map.type(), CV_8UC2);
    // Pixels 15 px off the border on either side: distance ~15, orientation that of the border.
    const double a = deg * std::numbers::pi / 180.0;
    for (const double side : {-15.0, 15.0}) {
      const int c = static_cast<int>(std::lround(80 + side * std::cos(a)));
      const int r = static_cast<int>(std::lround(60 + side * std::sin(a)));
      const cv::Vec2b v = map.at<cv::Vec2b>(r, c);
      EXPECT_NEAR(v[0], 15, 2.5) << deg;
      EXPECT_LE(angle_between(v[1], deg), 10) << deg;  // Canny's pixels of an aliased border
    }
  }
  // The distances are those of the plain map, to within the 5x5 mask's approximation.
  const cv::Mat rgb = half_plane(30);
  const cv::Mat plain = edge_distance_map(rgb);
  cv::Mat channels[2];
  cv::split(oriented_edge_map(rgb), channels);
  cv::Mat diff;
  cv::absdiff(plain, channels[0], diff);
  double worst = 0;
  cv::minMaxLoc(diff, nullptr, &worst);
  EXPECT_LE(worst, 2.0);
}

TEST(OrientedEdges, AContourTurnedAgainstTheEdgesItLiesOnCostsMore) {
  // The observed border has normal 30 deg; a contour on it costs ~0, the same contour turned by
  // 90 deg about the same point crosses the border: near it, perpendicular.
  const cv::Mat map = oriented_edge_map(half_plane(30));
  const double w = 20.0;
  const double aligned = mean_oriented_chamfer_distance(map, line_tile(30), w);
  const double turned45 = mean_oriented_chamfer_distance(map, line_tile(75), w);
  const double turned90 = mean_oriented_chamfer_distance(map, line_tile(120), w);
  EXPECT_LT(aligned, 2.0);
  EXPECT_LT(aligned, turned45);
  EXPECT_LT(turned45, turned90);
  // The orientation term alone: with no weight the costs are plain chamfer distances.
  EXPECT_GT(mean_oriented_chamfer_distance(map, line_tile(120), w) -
                mean_oriented_chamfer_distance(map, line_tile(120), 0.0),
            0.5 * w);
  EXPECT_DOUBLE_EQ(mean_oriented_chamfer_distance(map, cv::Mat::zeros(120, 160, CV_8U), w),
                   255.0 + w);
}

}  // namespace
}  // namespace somasim::body_schema
