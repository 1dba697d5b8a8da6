#pragma once
/// @file
/// Composition of several figures into one image (e.g. "ours" vs "authors'" maps).
#include <string>
#include <vector>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// Places the figures left to right, top-aligned on white, `gap_px` apart, under an optional
/// common title. Axes frames are shifted accordingly and concatenated in order.
/// Throws somasim::InputError when `panels` is empty or holds an empty image.
Figure compose_row(const std::vector<Figure>& panels, int gap_px = 0, const std::string& title = {},
                   double font_scale = 1.0);

/// Same, top to bottom (left-aligned).
Figure compose_column(const std::vector<Figure>& panels, int gap_px = 0,
                      const std::string& title = {}, double font_scale = 1.0);

}  // namespace somasim::figures
