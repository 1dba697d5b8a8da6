#pragma once
/// @file
/// Heatmap of a scalar field over a 2-D range, with a colour bar and optional overlays.
/// Typical use: the PPS activation "landscape" over D [cm] (x) x TTC [s] (y).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/figures/colormap.hpp"
#include "somasim/figures/figure.hpp"

namespace somasim::figures {

/// A rows x cols grid of values: row r runs along y (row 0 at y_min, at the BOTTOM of the plot),
/// column c along x (column 0 at x_min). NaN marks a missing value (drawn light grey).
struct Grid {
  int rows = 0;
  int cols = 0;
  std::vector<double> values;  ///< row-major: values[r * cols + c]

  /// From a row-major vector (sizes are checked when rendering).
  static Grid row_major(int rows, int cols, std::vector<double> values) {
    return Grid{rows, cols, std::move(values)};
  }
  /// From a matrix whose row index runs along y and column index along x (m(r, c)).
  /// A D-major (x-major) matrix such as an 8 x 4 D x TTC map needs `m.transpose()`.
  static Grid from_matrix(const Eigen::MatrixXd& m);
};

/// What a grid value stands for.
enum class GridLayout {
  /// Point samples on a lattice including both ends: column c at
  /// x_min + c * (x_max - x_min) / (cols - 1) (use for fine grids, e.g. 301 x 121).
  kSamples,
  /// Equal cells tiling the range: column c covers [x_min + c * w, x_min + (c + 1) * w)
  /// with w = (x_max - x_min) / cols (use for raw histograms, e.g. 8 x 4 bins).
  kCells,
};

/// How the grid is resampled to the plot pixels.
enum class Resampling { kNearest, kBilinear };

/// A polyline in data coordinates drawn over the heatmap (e.g. a regression line).
struct Polyline {
  std::vector<double> x, y;    ///< data coordinates; NaN breaks the line
  std::string label;           ///< legend entry; empty = not in the legend
  std::optional<Color> color;  ///< default: contrasting overlay colours (red, white, ...)
  double width_px = 2.5;
  LineStyle style = LineStyle::kSolid;
};

/// Markers in data coordinates drawn over the heatmap.
struct Points {
  std::vector<double> x, y;
  std::string label;  ///< legend entry; empty = not in the legend
  std::optional<Color> color;
  Marker marker = Marker::kCircle;
  double size_px = 9;  ///< marker diameter
};

struct HeatmapSpec {
  Grid grid;
  GridLayout layout = GridLayout::kSamples;
  Resampling resampling = Resampling::kBilinear;
  double x_min = 0, x_max = 1;  ///< data range along x (e.g. D [cm])
  double y_min = 0, y_max = 1;  ///< data range along y (e.g. TTC [s])

  std::string title;
  std::string x_label;         ///< include units, e.g. "D [cm]"
  std::string y_label;         ///< e.g. "TTC [s]"
  std::string colorbar_label;  ///< e.g. "activation"
  /// Values mapped to the ends of the colour map (clamped outside). nullopt: min/max of the
  /// finite values (a constant grid gets [v - 0.5, v + 0.5]).
  std::optional<Range> value_range = Range{0.0, 1.0};
  Colormap colormap = Colormap::kViridis;

  std::vector<Polyline> lines;
  std::vector<Points> points;
  /// Optional bin-edge grid lines (data units), drawn thin and semi-transparent white.
  std::vector<double> x_edges, y_edges;
  LegendPosition legend = LegendPosition::kBest;

  int width = 900, height = 600;  ///< [px] of the whole figure
  double font_scale = 1.0;        ///< multiplies all text sizes (1.0: ~14 px labels)
};

/// Renders the heatmap. Throws somasim::InputError on an empty grid, a grid whose value count is
/// not rows * cols, kSamples with fewer than 2 rows or columns, an empty or non-finite range,
/// overlays with mismatched x/y sizes, or a figure smaller than 200 x 150 px.
Figure render_heatmap(const HeatmapSpec& spec);

}  // namespace somasim::figures
