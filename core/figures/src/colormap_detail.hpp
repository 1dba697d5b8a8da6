#pragma once
// Private colour-map helpers shared by the heatmap and the colour bar.
#include <cstdint>

#include "somasim/figures/colormap.hpp"

namespace somasim::figures::detail {

/// Normalised value t -> level 0..255 (clamped; NaN -> 0).
std::uint8_t quantise(double t);

/// Colour of a quantised level.
Color level_color(Colormap map, std::uint8_t level);

}  // namespace somasim::figures::detail
