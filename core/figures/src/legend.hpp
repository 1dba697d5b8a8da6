#pragma once
// Private: legend box inside an axes.
#include <optional>
#include <string>
#include <vector>

#include "canvas.hpp"

namespace somasim::figures::detail {

struct LegendEntry {
  std::string label;
  Color color;
  bool line = true;  ///< draw a line sample
  LineStyle style = LineStyle::kSolid;
  double width_px = 2;
  std::optional<Marker> marker;
  double marker_px = 8;
  bool halo = false;  ///< white halo under the sample (heatmap overlays)
};

/// Draws the entries with a non-empty label; `data_px` are the plotted points in pixels (used by
/// kBest to pick the least covered corner).
void draw_legend(Canvas& canvas, const AxesFrame& f, const std::vector<LegendEntry>& entries,
                 LegendPosition pos, const Fonts& fonts, const std::vector<Point>& data_px);

}  // namespace somasim::figures::detail
