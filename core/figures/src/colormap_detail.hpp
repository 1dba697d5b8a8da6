#pragma once
// Private colour-map helpers shared by the heatmap and the colour bar.
#include <cstdint>

#include <opencv2/core.hpp>

#include "somasim/figures/colormap.hpp"

namespace somasim::figures::detail {

/// Normalised value t -> level 0..255 (clamped; NaN -> 0).
std::uint8_t quantise(double t);

/// CV_8UC1 levels -> CV_8UC3 BGR colours.
cv::Mat apply_colormap(const cv::Mat& levels, Colormap map);

}  // namespace somasim::figures::detail
