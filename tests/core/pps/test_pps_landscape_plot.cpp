// The landscape figure's overlays: Fig 8 regression line, floor estimate and true offset.
#include <gtest/gtest.h>

#include "somasim/pps/landscape_plot.hpp"
#include "somasim/pps/offset_floor.hpp"

using namespace somasim::pps;

namespace {

// Positive counts on a ridge D = 2 cm + 5 cm/s * TTC (1 cm bins): approaches ending 2 cm out.
TaxelMap ridge_map() {
  GridSpec g;
  g.d_bins = 30;
  g.ttc_max = 3.0;
  TaxelMap map(g, ParzenSpec::paper());
  for (int k = 0; k < 40; ++k)
    for (double t = 0.05; t < 2.9; t += 0.05) map.add_sample(0.02 + 0.05 * t, t, true, false);
  map.refresh();
  return map;
}

const somasim::figures::Polyline* line_labelled(const somasim::figures::HeatmapSpec& spec,
                                                const std::string& prefix) {
  for (const auto& l : spec.lines)
    if (l.label.rfind(prefix, 0) == 0) return &l;
  return nullptr;
}

}  // namespace

TEST(LandscapePlot, DrawsTheFloorEstimateAndTheTrueOffsetAsVerticalLines) {
  const TaxelMap map = ridge_map();
  LandscapeOptions options;
  options.true_offset_m = 0.025;
  const auto spec = landscape_heatmap(map, options);
  const auto floor = estimate_offset_floor(map);
  ASSERT_TRUE(floor.has_value());
  const auto* f = line_labelled(spec, "floor estimate: ");
  ASSERT_NE(f, nullptr);
  EXPECT_DOUBLE_EQ(f->x.front(), 100.0 * *floor);  // [cm]
  EXPECT_DOUBLE_EQ(f->x.back(), 100.0 * *floor);
  EXPECT_DOUBLE_EQ(f->y.front(), 0.0);
  EXPECT_DOUBLE_EQ(f->y.back(), 3.0);
  const auto* t = line_labelled(spec, "true offset: 2.5 cm");
  ASSERT_NE(t, nullptr);
  EXPECT_DOUBLE_EQ(t->x.front(), 2.5);
  EXPECT_NE(line_labelled(spec, "regression line (paper A, Fig. 8)"), nullptr);
}

TEST(LandscapePlot, OverlaysCanBeLeftOut) {
  LandscapeOptions options;
  options.regression_line = false;
  options.floor_line = false;
  options.true_offset_m = 0.5;  // outside the D range: not drawn
  EXPECT_TRUE(landscape_heatmap(ridge_map(), options).lines.empty());
}
