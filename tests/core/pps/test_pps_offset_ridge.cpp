// Ridge-end offset estimator on synthetic maps of straight approaches with known ends.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/pps/offset_estimate.hpp"
#include "somasim/pps/offset_ridge.hpp"

using namespace somasim::pps;

namespace {

// Positives of radial approaches at `speed` [m/s] sampled every 50 ms, from D = 0.25 m down to
// their end D = ends[k] (the last sample exactly at the end), unsigned TTC = |D| / speed.
// Negatives: a uniform background.
TaxelMap approaches(const std::vector<double>& ends, double speed, const GridSpec& g) {
  TaxelMap m(g, ParzenSpec::paper());
  for (double e : ends) {
    const double step = speed * 0.05;
    for (double d = e; d <= 0.25; d += step) m.add_sample(d, std::abs(d) / speed, true, false);
  }
  for (int k = 0; k < static_cast<int>(g.size()); ++k)
    for (int n = 0; n < 20; ++n) m.add_to_bin(k, false);
  m.refresh();
  return m;
}

std::vector<double> spread(double centre, double half_width, int n) {
  std::vector<double> v;
  for (int k = 0; k < n; ++k) v.push_back(centre - half_width + 2 * half_width * (k + 0.5) / n);
  return v;
}

}  // namespace

TEST(PpsOffsetRidge, RecoversTheMeanEndOfTheApproaches) {
  for (double end : {-0.03, -0.02, -0.01, 0.0, 0.02}) {
    const TaxelMap m = approaches(spread(end, 0.008, 40), 0.06, GridSpec::paper());
    const auto e = estimate_ridge_end(m);
    ASSERT_TRUE(e.has_value()) << end;
    EXPECT_DOUBLE_EQ(e->ref_m, 0.05);  // first D edge at or above 0.04 m
    EXPECT_NEAR(e->offset_m, end, 0.003) << end;
    EXPECT_NEAR(*estimate_offset_ridge(m), e->offset_m, 1e-15);
  }
}

TEST(PpsOffsetRidge, SubBinResolutionWhereFig8FollowsTheBand) {
  // Ends 1 cm apart, inside one D bin: the estimates are 1 cm apart too.
  const auto a =
      estimate_offset_ridge(approaches(spread(-0.015, 0.003, 30), 0.05, GridSpec::paper()));
  const auto b =
      estimate_offset_ridge(approaches(spread(-0.005, 0.003, 30), 0.05, GridSpec::paper()));
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(*b - *a, 0.01, 0.002);
  // With the unsigned TTC the band folds into a V around D = 0: Fig 8 reads far from the end.
  const TaxelMap m = approaches(spread(-0.02, 0.005, 30), 0.06, GridSpec::paper());
  EXPECT_NEAR(*estimate_offset_ridge(m), -0.02, 0.003);
  EXPECT_GT(std::abs(*estimate_offset(m) + 0.02), 0.01);
}

TEST(PpsOffsetRidge, ReferenceEdgeAndPlateauOptions) {
  const TaxelMap m = approaches(spread(-0.02, 0.005, 30), 0.06, GridSpec::paper());
  RidgeEndOptions o;
  o.ref_min_m = 0.08;  // edge 0.0875
  o.plateau_bins = 2;
  const auto e = estimate_ridge_end(m, o);
  ASSERT_TRUE(e.has_value());
  EXPECT_NEAR(e->ref_m, 0.0875, 1e-12);
  EXPECT_NEAR(e->offset_m, -0.02, 0.003);
  o.ref_min_m = 0.2;  // no bin above the edge
  EXPECT_FALSE(estimate_ridge_end(m, o).has_value());
}

TEST(PpsOffsetRidge, UndefinedWithoutAPlateau) {
  const TaxelMap empty(GridSpec::paper(), ParzenSpec::paper());
  EXPECT_FALSE(estimate_offset_ridge(empty).has_value());
  // Positives only below the reference edge.
  TaxelMap low(GridSpec::paper(), ParzenSpec::paper());
  for (int n = 0; n < 50; ++n) low.add_sample(0.0, 0.1, true);
  EXPECT_FALSE(estimate_offset_ridge(low).has_value());
}

TEST(PpsOffsetRidge, WorksOnADistanceOnlyMap) {
  const GridSpec g = distance_only_grid(GridSpec::paper());
  TaxelMap m(g, ParzenSpec::paper());
  for (double e : spread(-0.02, 0.005, 30))
    for (double d = e; d <= 0.25; d += 0.003) m.add_sample(d, 0.5, true, false);
  m.refresh();
  EXPECT_NEAR(*estimate_offset_ridge(m), -0.02, 0.003);
}
