#include "landscape_figure.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/figures/heatmap.hpp"
#include "somasim/pps/offset_estimate.hpp"

namespace somasim::plugins {
namespace {

constexpr int kSamplesD = 301;    // 1 mm steps over the default 30 cm range
constexpr int kSamplesTtc = 121;  // 25 ms steps over 3 s

figures::HeatmapSpec landscape_spec(const pps::TaxelMap& map, const std::string& title) {
  const pps::GridSpec& g = map.grid();
  figures::HeatmapSpec spec;
  std::vector<double> values(static_cast<std::size_t>(kSamplesD) * kSamplesTtc);
  for (int r = 0; r < kSamplesTtc; ++r)
    for (int c = 0; c < kSamplesD; ++c) {
      const double d = g.d_min + (g.d_max - g.d_min) * c / (kSamplesD - 1);
      const double t = g.ttc_min + (g.ttc_max - g.ttc_min) * r / (kSamplesTtc - 1);
      values[static_cast<std::size_t>(r) * kSamplesD + c] = map.activation(d, t);
    }
  spec.grid = figures::Grid::row_major(kSamplesTtc, kSamplesD, std::move(values));
  spec.x_min = 100.0 * g.d_min;
  spec.x_max = 100.0 * g.d_max;
  spec.y_min = g.ttc_min;
  spec.y_max = g.ttc_max;
  for (int i = 0; i <= g.d_bins; ++i) spec.x_edges.push_back(100.0 * (g.d_min + i * g.d_width()));
  for (int j = 0; j <= g.ttc_bins; ++j) spec.y_edges.push_back(g.ttc_min + j * g.ttc_width());
  spec.title = title;
  spec.x_label = "D [cm]";
  spec.y_label = "TTC [s]";
  spec.colorbar_label = "activation";
  return spec;
}

// The Fig 8 regression line, clipped to the plotted range, with its TTC = 0 crossing.
void add_regression(figures::HeatmapSpec& spec, const pps::TaxelMap& map) {
  const auto line = pps::fit_activation_line(map);
  const auto offset = pps::estimate_offset(map);
  if (!line || !offset) return;
  const pps::GridSpec& g = map.grid();
  figures::Polyline pl;
  const int n = 200;
  for (int k = 0; k <= n; ++k) {
    // Parametrise along TTC when possible (the line is steep in these axes).
    const double t = g.ttc_min + (g.ttc_max - g.ttc_min) * k / n;
    const double d =
        line->centre.x() + (t - line->centre.y()) * line->direction.x() / line->direction.y();
    const bool inside = d >= g.d_min && d <= g.d_max;
    pl.x.push_back(inside ? 100.0 * d : NAN);
    pl.y.push_back(inside ? t : NAN);
  }
  pl.label = fmt::format("regression (Fig 8): D = {:.1f} cm at TTC = 0", 100.0 * *offset);
  pl.color = figures::Color{230, 30, 30};
  spec.lines.push_back(std::move(pl));
}

}  // namespace

void draw_landscapes(NodeContext& ctx, pps::BodyPartLearner& learner,
                     const std::vector<double>& taxel_ids, const std::string& suffix) {
  std::vector<int> indices;
  if (taxel_ids.empty()) {
    for (int k = 0; k < static_cast<int>(learner.taxels().size()) && k < 4; ++k)
      indices.push_back(k);
  } else {
    for (double id : taxel_ids) {
      const int k = learner.index_of(static_cast<int>(id));
      if (k >= 0) indices.push_back(k);
    }
  }
  for (int k : indices) {
    pps::TaxelMap& map = learner.maps()[k];
    if (map.stale()) map.refresh();
    const int id = learner.taxels()[k].id;
    std::uint64_t samples = 0;
    for (std::size_t i = 0; i < map.pos().size(); ++i) samples += map.pos()[i] + map.neg()[i];
    std::string when = suffix.empty() ? "" : ", " + suffix;
    std::replace(when.begin(), when.end(), '_', ' ');
    auto spec = landscape_spec(
        map, fmt::format("{}, taxel {}: {} samples{}", learner.body_part(), id, samples, when));
    add_regression(spec, map);
    const std::string file = fmt::format("landscape_{}_{}{}.png", learner.body_part(), id,
                                         suffix.empty() ? "" : "_" + suffix);
    figures::save_png(figures::render_heatmap(spec), ctx.figure_path(file));
  }
}

}  // namespace somasim::plugins
