#pragma once
/// @file
/// Colour maps for heatmaps and colour bars.
#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// Colour maps (OpenCV's look-up tables). kViridis is perceptually uniform and readable in
/// greyscale print; kJet matches older papers.
enum class Colormap { kViridis, kPlasma, kInferno, kMagma, kCividis, kTurbo, kJet, kGray };

/// Colour of normalised value t (clamped to [0, 1]) after quantisation to 256 levels: exactly the
/// colour a heatmap pixel of that normalised value gets.
Color colormap_color(Colormap map, double t);

}  // namespace somasim::figures
