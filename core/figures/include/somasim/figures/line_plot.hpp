#pragma once
/// @file
/// Line plots of one or more series, and stacked panels sharing the x axis (time series).
#include <optional>
#include <string>
#include <vector>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// One curve. NaN in x or y breaks the line (a gap).
struct Series {
  std::vector<double> x, y;
  std::string label;           ///< legend entry; empty = not in the legend
  std::optional<Color> color;  ///< default: next palette() colour
  double width_px = 2.0;
  LineStyle style = LineStyle::kSolid;
  std::optional<Marker> marker;  ///< also mark every sample
};

/// A horizontal (y = value) or vertical (x = value) reference line across the axes,
/// e.g. an activation threshold.
struct RefLine {
  double value = 0;
  std::string label;           ///< legend entry; empty = not in the legend
  std::optional<Color> color;  ///< default: dark grey
  LineStyle style = LineStyle::kDashed;
  double width_px = 1.5;
};

/// One axes of line plots.
struct LinePlotSpec {
  std::string title;    ///< figure title (single plot) or panel title (stacked)
  std::string x_label;  ///< ignored in stacked panels (the stack has one)
  std::string y_label;
  std::vector<Series> series;
  std::vector<RefLine> hlines;   ///< y = value
  std::vector<RefLine> vlines;   ///< x = value
  std::optional<Range> x_range;  ///< default: data extent (ignored in stacked panels)
  std::optional<Range> y_range;  ///< default: data and hlines extent, padded by 5 %
  bool grid = true;              ///< light grid lines at the ticks
  LegendPosition legend = LegendPosition::kBest;

  int width = 900, height = 600;  ///< [px] (single plot only)
  double font_scale = 1.0;
};

/// Renders a single line plot. Throws somasim::InputError when a series has different x and y
/// sizes, a range is empty or not finite, or the figure is smaller than 200 x 150 px.
/// A plot without any finite data gets the range [0, 1].
Figure render_line_plot(const LinePlotSpec& spec);

/// Panels stacked vertically, sharing one x axis (tick labels and x_label only on the bottom).
struct StackedPlotSpec {
  std::string title;
  std::string x_label;
  std::optional<Range> x_range;      ///< default: extent of all panels' data
  std::vector<LinePlotSpec> panels;  ///< top to bottom; their width/height/x_* are ignored
  int width = 900;
  int panel_height = 220;  ///< [px] plot height of each panel
  double font_scale = 1.0;
};

/// Renders stacked panels (Figure::axes lists them top to bottom). Throws somasim::InputError
/// when there are no panels, or as render_line_plot.
Figure render_stacked(const StackedPlotSpec& spec);

}  // namespace somasim::figures
