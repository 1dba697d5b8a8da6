#include "somasim/body_schema/likelihood.hpp"

#include <fmt/format.h>

#include <cmath>

#include "somasim/error.hpp"

namespace somasim::body_schema {

SilhouetteForm silhouette_form_from_name(std::string_view name) {
  if (const auto form = parse_enum<SilhouetteForm>(name)) return *form;
  throw InputError(
      fmt::format("unknown silhouette likelihood '{}' (expected jaccard or power)", name));
}

MaskObservation cut_to_roi(const cv::Mat& observed_mask, const cv::Rect& roi) {
  CV_Assert(observed_mask.type() == CV_8U);
  MaskObservation obs;
  obs.roi_mask = observed_mask(roi).clone();
  obs.outside = cv::countNonZero(observed_mask) - cv::countNonZero(obs.roi_mask);
  return obs;
}

double jaccard(const MaskObservation& obs, const cv::Mat& hypothesis_tile) {
  CV_Assert(hypothesis_tile.type() == CV_8U && hypothesis_tile.size() == obs.roi_mask.size());
  // |O ∪ H| = |O| + |H| − |O ∩ H|; OpenCV's vectorised AND and counts (masks are 0 / 255).
  cv::Mat both;
  cv::bitwise_and(obs.roi_mask, hypothesis_tile, both);
  const std::int64_t common = cv::countNonZero(both);
  const std::int64_t either =
      cv::countNonZero(obs.roi_mask) + cv::countNonZero(hypothesis_tile) - common + obs.outside;
  return either == 0 ? 0.0 : static_cast<double>(common) / static_cast<double>(either);
}

double silhouette_likelihood(double jaccard_index, SilhouetteForm form, double power) {
  return form == SilhouetteForm::kJaccard ? jaccard_index : std::pow(jaccard_index, power);
}

double mean_chamfer_distance(const cv::Mat& distance_roi, const cv::Mat& contour_tile) {
  CV_Assert(distance_roi.type() == CV_8U && contour_tile.type() == CV_8U &&
            distance_roi.size() == contour_tile.size());
  std::int64_t sum = 0, count = 0;
  for (int r = 0; r < contour_tile.rows; ++r) {
    const std::uint8_t* d = distance_roi.ptr<std::uint8_t>(r);
    const std::uint8_t* e = contour_tile.ptr<std::uint8_t>(r);
    for (int c = 0; c < contour_tile.cols; ++c) {
      if (e[c] == 0) continue;
      sum += d[c];
      ++count;
    }
  }
  return count == 0 ? 255.0 : static_cast<double>(sum) / static_cast<double>(count);
}

double edge_likelihood(double mean_distance_px, double lambda_per_px) {
  return std::exp(-lambda_per_px * mean_distance_px);
}

}  // namespace somasim::body_schema
