#include "somasim/pps/landscape_plot.hpp"

#include <cmath>

#include <fmt/format.h>

#include "somasim/pps/offset_estimate.hpp"
#include "somasim/pps/offset_floor.hpp"

namespace somasim::pps {
namespace {

// The Fig 8 regression line, clipped to the plotted range, labelled with its TTC = 0 crossing.
void add_regression(figures::HeatmapSpec& spec, const TaxelMap& map) {
  const auto line = fit_activation_line(map);
  const auto offset = estimate_offset(map);
  if (!line || !offset) return;
  const GridSpec& g = map.grid();
  figures::Polyline pl;
  constexpr int kPoints = 200;
  for (int k = 0; k <= kPoints; ++k) {
    // Parametrised along TTC: the line is never horizontal when an offset exists.
    const double t = g.ttc_min + (g.ttc_max - g.ttc_min) * k / kPoints;
    const double d =
        line->centre.x() + (t - line->centre.y()) * line->direction.x() / line->direction.y();
    const bool inside = d >= g.d_min && d <= g.d_max;
    pl.x.push_back(inside ? 100.0 * d : NAN);
    pl.y.push_back(inside ? t : NAN);
  }
  pl.label =
      fmt::format("regression line (paper A, Fig. 8): D = {:.1f} cm at TTC = 0", 100.0 * *offset);
  pl.color = figures::Color{230, 30, 30};
  spec.lines.push_back(std::move(pl));
}

// A vertical line at D = `d_m` over the whole TTC range (nothing when outside the D range).
void add_vertical(figures::HeatmapSpec& spec, const TaxelMap& map, double d_m, std::string label,
                  figures::Color color) {
  const GridSpec& g = map.grid();
  if (d_m < g.d_min || d_m > g.d_max) return;
  figures::Polyline pl;
  pl.x = {100.0 * d_m, 100.0 * d_m};
  pl.y = {g.ttc_min, g.ttc_max};
  pl.label = std::move(label);
  pl.color = color;
  spec.lines.push_back(std::move(pl));
}

}  // namespace

figures::HeatmapSpec landscape_heatmap(const TaxelMap& map, const LandscapeOptions& options) {
  const GridSpec& g = map.grid();
  const int nd = options.d_samples, nt = options.ttc_samples;
  std::vector<double> values(static_cast<std::size_t>(nd) * nt);
  for (int r = 0; r < nt; ++r)
    for (int c = 0; c < nd; ++c) {
      const double d = g.d_min + (g.d_max - g.d_min) * c / (nd - 1);
      const double t = g.ttc_min + (g.ttc_max - g.ttc_min) * r / (nt - 1);
      values[static_cast<std::size_t>(r) * nd + c] = map.activation(d, t);
    }
  figures::HeatmapSpec spec;
  spec.grid = figures::Grid::row_major(nt, nd, std::move(values));
  spec.x_min = 100.0 * g.d_min;
  spec.x_max = 100.0 * g.d_max;
  spec.y_min = g.ttc_min;
  spec.y_max = g.ttc_max;
  if (options.bin_grid) {
    for (int i = 0; i <= g.d_bins; ++i) spec.x_edges.push_back(100.0 * (g.d_min + i * g.d_width()));
    for (int j = 0; j <= g.ttc_bins; ++j) spec.y_edges.push_back(g.ttc_min + j * g.ttc_width());
  }
  spec.title = options.title;
  spec.x_label = "distance to the taxel, D [cm]";
  spec.y_label = "time to contact, TTC [s]";
  spec.colorbar_label = "activation (probability of contact)";
  if (options.regression_line) add_regression(spec, map);
  if (options.floor_line)
    if (const auto floor = estimate_offset_floor(map))
      add_vertical(spec, map, *floor, fmt::format("floor estimate: {:.1f} cm", 100.0 * *floor),
                   figures::Color{255, 255, 255});
  if (options.true_offset_m)
    add_vertical(spec, map, *options.true_offset_m,
                 fmt::format("true offset: {:.1f} cm", 100.0 * *options.true_offset_m),
                 figures::Color{255, 140, 0});
  return spec;
}

}  // namespace somasim::pps
