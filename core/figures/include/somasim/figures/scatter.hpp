#pragma once
/// @file
/// Scatter plots of 2-D points, grouped into categories (one colour and legend entry each).
#include <optional>
#include <string>
#include <vector>

#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// Points of one category.
struct ScatterGroup {
  std::vector<double> x, y;
  std::string label;           ///< legend entry; empty = not in the legend
  std::optional<Color> color;  ///< default: next palette() colour
  Marker marker = Marker::kCircle;
  double size_px = 8;                    ///< marker diameter
  std::vector<std::string> annotations;  ///< optional text next to each point (empty or x.size())
};

struct ScatterSpec {
  std::string title, x_label, y_label;
  std::vector<ScatterGroup> groups;
  std::optional<Range> x_range, y_range;  ///< default: data extent padded by 5 %
  bool equal_aspect = false;  ///< one data unit has the same length on both axes (layouts)
  bool grid = true;
  LegendPosition legend = LegendPosition::kBest;
  int width = 900, height = 600;
  double font_scale = 1.0;
};

/// Groups points by an integer category: one ScatterGroup per distinct category, in ascending
/// order, labelled `labels[i]` for the i-th category when given (else the number). Throws
/// somasim::InputError when x, y and category sizes differ.
std::vector<ScatterGroup> group_by_category(const std::vector<double>& x,
                                            const std::vector<double>& y,
                                            const std::vector<int>& category,
                                            const std::vector<std::string>& labels = {});

/// Renders the scatter plot. Throws somasim::InputError on mismatched sizes, an empty or
/// non-finite range, or a figure smaller than 200 x 150 px.
Figure render_scatter(const ScatterSpec& spec);

}  // namespace somasim::figures
