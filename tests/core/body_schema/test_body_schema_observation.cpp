// Observations from RGB images (colour silhouettes, edge distance maps) and the likelihoods
// computed from them against hypothesis tiles.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "somasim/body_schema/likelihood.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/error.hpp"

namespace somasim::body_schema {
namespace {

// White image with a skin-coloured (R, G, B) rectangle and a grey one.
cv::Mat scene() {
  cv::Mat rgb(120, 160, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::rectangle(rgb, cv::Rect(40, 30, 50, 40), cv::Scalar(224, 172, 140), cv::FILLED);
  cv::rectangle(rgb, cv::Rect(100, 80, 30, 20), cv::Scalar(190, 190, 190), cv::FILLED);
  return rgb;
}

TEST(Observation, ColourSegmentationKeepsTheSkinColouredRegionOnly) {
  const cv::Mat mask = segment_colour(scene(), HsvRange{});
  EXPECT_EQ(cv::countNonZero(mask), 50 * 40);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(40, 30, 50, 40))), 50 * 40);
}

TEST(Observation, EdgeDistanceIsZeroOnEdgesAndGrowsAwayFromThem) {
  const cv::Mat d = edge_distance_map(scene());
  ASSERT_EQ(d.type(), CV_8U);
  // The skin rectangle's left edge (column 40 or its neighbour) carries an edge; its centre is
  // about 20 px from the nearest edge; the far corner of the image is much farther.
  EXPECT_EQ(std::min(d.at<std::uint8_t>(50, 39), d.at<std::uint8_t>(50, 40)), 0);
  EXPECT_NEAR(d.at<std::uint8_t>(50, 65), 20, 2);
  EXPECT_GT(d.at<std::uint8_t>(5, 155), 30);
}

TEST(Likelihood, JaccardCountsObservedPixelsOutsideTheRegionOfInterest) {
  cv::Mat observed = cv::Mat::zeros(100, 100, CV_8U);
  observed(cv::Rect(10, 10, 20, 10)).setTo(255);  // 200 px
  const cv::Rect roi(0, 0, 20, 30);               // holds 100 of them
  const MaskObservation obs = cut_to_roi(observed, roi);
  EXPECT_EQ(obs.outside, 100);
  cv::Mat h = cv::Mat::zeros(roi.size(), CV_8U);
  h(cv::Rect(10, 10, 10, 10)).setTo(255);  // exactly the 100 observed px in the ROI
  EXPECT_DOUBLE_EQ(jaccard(obs, h), 0.5);
  h(cv::Rect(0, 0, 10, 10)).setTo(255);  // 100 more px, none observed
  EXPECT_DOUBLE_EQ(jaccard(obs, h), 100.0 / 300.0);
  EXPECT_DOUBLE_EQ(
      jaccard(cut_to_roi(cv::Mat::zeros(100, 100, CV_8U), roi), cv::Mat::zeros(roi.size(), CV_8U)),
      0.0);
}

TEST(Likelihood, FormsAndEdgeLikelihood) {
  EXPECT_DOUBLE_EQ(silhouette_likelihood(0.8, SilhouetteForm::kJaccard, 10.0), 0.8);
  EXPECT_NEAR(silhouette_likelihood(0.8, SilhouetteForm::kPower, 10.0), std::pow(0.8, 10), 1e-15);
  EXPECT_EQ(silhouette_form_from_name("power"), SilhouetteForm::kPower);
  try {
    silhouette_form_from_name("dice");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown silhouette likelihood 'dice' (expected jaccard or power)");
  }
  EXPECT_NEAR(edge_likelihood(10.0, 0.01), std::exp(-0.1), 1e-15);
  cv::Mat d(4, 4, CV_8U, cv::Scalar(7));
  d.at<std::uint8_t>(0, 0) = 1;
  cv::Mat e = cv::Mat::zeros(4, 4, CV_8U);
  e.at<std::uint8_t>(0, 0) = 255;
  e.at<std::uint8_t>(3, 3) = 255;
  EXPECT_DOUBLE_EQ(mean_chamfer_distance(d, e), 4.0);
  EXPECT_DOUBLE_EQ(mean_chamfer_distance(d, cv::Mat::zeros(4, 4, CV_8U)), 255.0);
}

}  // namespace
}  // namespace somasim::body_schema
