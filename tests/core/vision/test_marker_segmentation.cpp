// Marker segmentation: a drawn green disc among skin-coloured and other blobs.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "somasim/error.hpp"
#include "somasim/vision/marker_segmentation.hpp"

namespace vision = somasim::vision;

namespace {

// A 320 × 240 rgb8 image (R, G, B) on a grey-blue background.
cv::Mat background() {
  return cv::Mat(240, 320, CV_8UC3, cv::Scalar(89, 115, 140));
}

std::string error_of(const cv::Mat& image, int min_area = 1) {
  try {
    vision::segment_marker(image, {}, min_area);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(MarkerSegmentation, FindsTheCentreAndAreaOfAGreenDisc) {
  cv::Mat image = background();
  cv::circle(image, {100, 80}, 40, cv::Scalar(237, 189, 153), cv::FILLED);  // skin (R, G, B)
  cv::circle(image, {203, 131}, 7, cv::Scalar(25, 217, 25), cv::FILLED);    // the marker
  cv::circle(image, {40, 200}, 2, cv::Scalar(25, 217, 25), cv::FILLED);     // a smaller speck
  const vision::MarkerBlob blob = vision::segment_marker(image, {}, 20);
  ASSERT_TRUE(blob.found);
  EXPECT_NEAR(blob.centroid_px.x(), 203.0, 1e-9);  // a symmetric disc: exact centre
  EXPECT_NEAR(blob.centroid_px.y(), 131.0, 1e-9);
  EXPECT_NEAR(blob.area_px, 3.14159 * 49, 15);
  EXPECT_GT(blob.matched_px, blob.area_px);  // the speck matched too
}

// A marker half hidden (behind the finger it sits on): the enclosing circle keeps its centre,
// the centroid moves 4 r / (3 pi) toward the visible half.
TEST(MarkerSegmentation, EnclosingCircleOfAHalfHiddenDisc) {
  cv::Mat image = background();
  cv::circle(image, {160, 120}, 12, cv::Scalar(25, 217, 25), cv::FILLED);
  cv::rectangle(image, {140, 121}, {180, 140}, cv::Scalar(237, 189, 153), cv::FILLED);  // finger
  const vision::MarkerBlob blob = vision::segment_marker(image, {});
  ASSERT_TRUE(blob.found);
  EXPECT_LT((blob.circle_centre_px - Eigen::Vector2d(160, 120)).norm(), 0.6);
  EXPECT_NEAR(blob.circle_radius_px, 12.0, 0.6);
  EXPECT_NEAR(blob.centroid_px.y(), 120 - 4 * 12 / (3 * 3.14159), 0.6);
}

TEST(MarkerSegmentation, ShadedGreenMatchesButSkinDoesNot) {
  cv::Mat image = background();
  // The marker's albedo at the darkest shading (ambient 0.3) is still green.
  cv::circle(image, {160, 120}, 6, cv::Scalar(8, 65, 8), cv::FILLED);
  cv::rectangle(image, {10, 10}, {60, 60}, cv::Scalar(237, 189, 153), cv::FILLED);
  cv::rectangle(image, {250, 10}, {300, 60}, cv::Scalar(71, 57, 46), cv::FILLED);  // dark skin
  const vision::MarkerBlob blob = vision::segment_marker(image, {});
  ASSERT_TRUE(blob.found);
  EXPECT_EQ(blob.matched_px, blob.area_px);
  EXPECT_NEAR(blob.centroid_px.x(), 160.0, 1e-9);
}

TEST(MarkerSegmentation, NothingInRangeOrTooSmallIsNotFound) {
  cv::Mat image = background();
  EXPECT_FALSE(vision::segment_marker(image, {}).found);
  EXPECT_EQ(vision::segment_marker(image, {}).matched_px, 0);
  cv::circle(image, {160, 120}, 2, cv::Scalar(25, 217, 25), cv::FILLED);
  const vision::MarkerBlob small = vision::segment_marker(image, {}, 50);
  EXPECT_FALSE(small.found);
  EXPECT_GT(small.area_px, 0);
}

TEST(MarkerSegmentation, HueRangeCanWrapAroundRed) {
  cv::Mat image = background();
  cv::circle(image, {50, 50}, 5, cv::Scalar(220, 20, 30), cv::FILLED);   // hue ~177
  cv::circle(image, {250, 50}, 8, cv::Scalar(220, 30, 20), cv::FILLED);  // hue ~2
  vision::HsvRange red;
  red.low = {170, 100, 50};
  red.high = {10, 255, 255};
  EXPECT_EQ(vision::segment_marker(image, red).centroid_px, Eigen::Vector2d(250, 50));
  EXPECT_NEAR(vision::segment_marker(image, red).matched_px, 3.14159 * (25 + 64), 25);
}

TEST(MarkerSegmentation, AllBlobsLargestFirst) {
  cv::Mat image = background();
  cv::circle(image, {50, 50}, 4, cv::Scalar(25, 217, 25), cv::FILLED);
  cv::circle(image, {150, 50}, 9, cv::Scalar(25, 217, 25), cv::FILLED);
  cv::circle(image, {250, 50}, 6, cv::Scalar(25, 217, 25), cv::FILLED);
  cv::circle(image, {250, 200}, 1, cv::Scalar(25, 217, 25), cv::FILLED);  // below min_area_px
  const auto blobs = vision::segment_blobs(image, {}, 10, 8);
  ASSERT_EQ(blobs.size(), 3u);
  EXPECT_EQ(blobs[0].circle_centre_px, Eigen::Vector2d(150, 50));
  EXPECT_EQ(blobs[1].circle_centre_px, Eigen::Vector2d(250, 50));
  EXPECT_EQ(blobs[2].circle_centre_px, Eigen::Vector2d(50, 50));
  EXPECT_NEAR(blobs[0].circle_radius_px, 9.0, 0.6);
  for (const auto& b : blobs) {
    EXPECT_TRUE(b.found);
    EXPECT_EQ(b.matched_px, cv::countNonZero(vision::hsv_mask(image, {})));
  }
  EXPECT_EQ(vision::segment_blobs(image, {}, 10, 2).size(), 2u);
  EXPECT_TRUE(vision::segment_blobs(background(), {}, 1, 8).empty());
}

TEST(MarkerSegmentation, BadImagesAreClearErrors) {
  EXPECT_EQ(error_of(cv::Mat()),
            "segment_marker: expected an rgb8 image (CV_8UC3), got an empty image");
  EXPECT_EQ(error_of(cv::Mat(4, 4, CV_32F, cv::Scalar(0))),
            "segment_marker: expected an rgb8 image (CV_8UC3), got CV_32FC1");
  EXPECT_EQ(error_of(background(), 0), "segment_marker: min_area_px: expected >= 1, got 0");
}
