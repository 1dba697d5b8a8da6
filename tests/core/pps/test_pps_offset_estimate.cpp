#include <cmath>

#include <gtest/gtest.h>

#include "somasim/pps/offset_estimate.hpp"

using namespace somasim::pps;

namespace {

// A map whose positives lie on the line D = d0 + slope * TTC (bin centres), negatives elsewhere.
TaxelMap ridge(double d0, double slope) {
  const GridSpec g = GridSpec::paper();  // TTC up to 3 s
  TaxelMap m(g, ParzenSpec::paper());
  for (int j = 0; j < g.ttc_bins; ++j) {
    const double t = g.ttc_min + (j + 0.5) * g.ttc_width();
    const double d = d0 + slope * t;
    for (int i = 0; i < g.d_bins; ++i) {
      const double lo = g.d_min + i * g.d_width();
      const bool on = d >= lo && d < lo + g.d_width();
      for (int n = 0; n < 10; ++n) m.add_to_bin(g.index(i, j), on);
    }
  }
  m.refresh();
  return m;
}

}  // namespace

TEST(PpsOffsetEstimate, RidgeThroughZero) {
  const auto off = estimate_offset(ridge(0.0, 0.05));
  ASSERT_TRUE(off.has_value());
  EXPECT_NEAR(*off, 0.0, 0.02);
}

TEST(PpsOffsetEstimate, RidgeThroughMinusTenCentimetres) {
  const auto off = estimate_offset(ridge(-0.10, 0.05));
  ASSERT_TRUE(off.has_value());
  EXPECT_LT(*off, -0.06);
  EXPECT_NEAR(*off, -0.10, 0.03);
  EXPECT_LT(*off, *estimate_offset(ridge(0.0, 0.05)));
}

TEST(PpsOffsetEstimate, EmptyMapIsUndefined) {
  const TaxelMap m(GridSpec::paper(), ParzenSpec::paper());
  EXPECT_FALSE(estimate_offset(m).has_value());
}

TEST(PpsOffsetEstimate, RidgeParallelToDIsUndefined) {
  // Positives only in one TTC bin, across all D: the line never meets TTC = 0.
  const GridSpec g = GridSpec::paper();
  TaxelMap m(g, ParzenSpec::paper());
  for (int i = 0; i < g.d_bins; ++i) m.add_to_bin(g.index(i, 2), true);
  m.refresh();
  EXPECT_FALSE(estimate_offset(m).has_value());
}
