#pragma once
/// @file
/// Likelihoods of one hypothesis (particle) given the observation of one camera, from the
/// hypothesis's silhouette or contour tile (somasim::render hypothesis batches: CV_8U 0 / 255,
/// the size of the camera's region of interest).
///
/// Silhouette: Jaccard index J = |O ∩ H| / |O ∪ H| of the observed mask O (whole image) and the
/// hypothesis mask H (inside the ROI, empty outside it). Likelihood forms (SilhouetteForm):
/// - `jaccard`: L = J (the paper's p ∝ sJc);
/// - `power`: L = J^k. The Jaccard index of near-misses differs little (0.8 vs 0.9), so L = J
///   weights good and poor particles almost alike and resampling barely selects; a power
///   sharpens the selection without changing the ranking (default k: see the plugin).
/// Over both eyes the likelihoods multiply.
///
/// Edges: d̄ = mean of the observed distance map (edge_distance_map, [px]) under the
/// hypothesis's contour pixels; L = exp(−λ d̄) with λ [1/px] (text 0.01, code 25/255).
#include <cstdint>
#include <span>
#include <string_view>

#include <opencv2/core.hpp>

#include "somasim/name_table.hpp"

namespace somasim::body_schema {

enum class SilhouetteForm : std::uint8_t { kJaccard, kPower };
inline constexpr NamedValue<SilhouetteForm> kSilhouetteFormNames[] = {
    {SilhouetteForm::kJaccard, "jaccard"}, {SilhouetteForm::kPower, "power"}};
/// "jaccard", "power".
constexpr std::span<const NamedValue<SilhouetteForm>> name_table(SilhouetteForm) {
  return kSilhouetteFormNames;
}
/// "jaccard" or "power"; InputError "unknown silhouette likelihood 'X' (expected jaccard or
/// power)" otherwise.
SilhouetteForm silhouette_form_from_name(std::string_view name);

/// The observation of one camera cut to a hypothesis batch's ROI.
struct MaskObservation {
  cv::Mat roi_mask;          ///< O inside the ROI (CV_8U 0 / 255)
  std::int64_t outside = 0;  ///< |O| outside the ROI [px]
};
MaskObservation cut_to_roi(const cv::Mat& observed_mask, const cv::Rect& roi);

/// Jaccard index of the observation and a hypothesis tile (same size as obs.roi_mask); 0 when
/// both are empty.
double jaccard(const MaskObservation& obs, const cv::Mat& hypothesis_tile);

double silhouette_likelihood(double jaccard_index, SilhouetteForm form, double power);

/// Mean of `distance_roi` (CV_8U [px]) under the non-zero pixels of `contour_tile`; 255 (the
/// farthest) when the contour is empty.
double mean_chamfer_distance(const cv::Mat& distance_roi, const cv::Mat& contour_tile);
double edge_likelihood(double mean_distance_px, double lambda_per_px);

}  // namespace somasim::body_schema
