#pragma once
// Private: vertical colour bar with ticks and a label, right of a heatmap.
#include <string>

#include "canvas.hpp"
#include "somasim/figures/colormap.hpp"

namespace somasim::figures::detail {

inline constexpr int kColorbarGap = 22;    // [px] between plot area and bar
inline constexpr int kColorbarWidth = 22;  // [px] bar width

/// Total width [px] right of the plot area taken by gap, bar, tick labels and label.
int colorbar_total_width(Range values, int bar_height, const std::string& label,
                         const Fonts& fonts);

/// Draws the bar in `bar` (values increase upwards), ticks and labels to its right.
void draw_colorbar(Canvas& canvas, Rect bar, Colormap map, Range values, const std::string& label,
                   const Fonts& fonts);

}  // namespace somasim::figures::detail
