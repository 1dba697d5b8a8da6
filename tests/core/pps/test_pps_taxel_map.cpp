#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "reference_counts.hpp"
#include "somasim/pps/taxel_map.hpp"

using namespace somasim::pps;

TEST(PpsGrid, BinEdges) {
  const GridSpec g = GridSpec::code();
  int i = -1, j = -1;
  ASSERT_TRUE(g.bin_of(-0.10, 0.0, i, j));
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 0);
  ASSERT_TRUE(g.bin_of(0.20, 1.2, i, j));  // upper edges go to the last bin
  EXPECT_EQ(i, 7);
  EXPECT_EQ(j, 3);
  ASSERT_TRUE(g.bin_of(-0.10 + 0.0375 * 2.5, 0.3 * 1.5, i, j));
  EXPECT_EQ(i, 2);
  EXPECT_EQ(j, 1);
  EXPECT_FALSE(g.bin_of(-0.1001, 0.5, i, j));
  EXPECT_FALSE(g.bin_of(0.2001, 0.5, i, j));
  EXPECT_FALSE(g.bin_of(0.0, -1e-9, i, j));
  EXPECT_FALSE(g.bin_of(0.0, 1.2001, i, j));
  EXPECT_FALSE(g.bin_of(std::nan(""), 0.5, i, j));
  EXPECT_EQ(g.index(2, 1), 9);
}

TEST(PpsTaxelMap, AddSampleAndRatio) {
  TaxelMap m(GridSpec::paper(), ParzenSpec::paper());
  EXPECT_TRUE(m.add_sample(0.0, 0.5, true));
  EXPECT_TRUE(m.add_sample(0.0, 0.5, true));
  EXPECT_TRUE(m.add_sample(0.0, 0.5, false));
  EXPECT_FALSE(m.add_sample(0.25, 0.5, true));
  EXPECT_FALSE(m.add_sample(0.0, 3.5, false));
  int i = 0, j = 0;
  ASSERT_TRUE(m.grid().bin_of(0.0, 0.5, i, j));
  EXPECT_DOUBLE_EQ(m.ratio(i, j), 2.0 / 3.0);
  EXPECT_EQ(m.ratio(0, 0), 0.0);
  EXPECT_EQ(m.pos()[m.grid().index(i, j)], 2u);
  EXPECT_EQ(m.neg()[m.grid().index(i, j)], 1u);
  // The peak anchor of a single-bin map has activation 1.
  const double cd = m.grid().d_min + (i + 0.5) * m.grid().d_width();
  const double ct = m.grid().ttc_min + (j + 0.5) * m.grid().ttc_width();
  EXPECT_NEAR(m.activation(cd, ct), 1.0, 1e-12);
}

TEST(PpsTaxelMap, EmptyMapAndOutsideRangesGiveZero) {
  TaxelMap m(GridSpec::code(), ParzenSpec::code());
  EXPECT_EQ(m.activation(0.0, 0.5), 0.0);
  m.add_sample(0.0, 0.5, true);
  EXPECT_GT(m.activation(0.0, 0.5), 0.0);
  EXPECT_EQ(m.activation(-0.11, 0.5), 0.0);
  EXPECT_EQ(m.activation(0.0, 1.3), 0.0);
  EXPECT_EQ(m.activation(0.0, -0.1), 0.0);
}

TEST(PpsTaxelMap, DeferredRefresh) {
  TaxelMap m(GridSpec::code(), ParzenSpec::code());
  m.add_sample(0.0, 0.5, true, false);
  EXPECT_TRUE(m.stale());
  m.refresh();
  EXPECT_FALSE(m.stale());
  EXPECT_GT(m.normaliser(), 0.0);
}

TEST(PpsTaxelMap, FastMatchesNaive) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cnt(0, 20);
  for (const ParzenSpec pz : {ParzenSpec::paper(), ParzenSpec::code()}) {
    std::vector<TaxelMap::Count> pos(32), neg(32);
    for (int k = 0; k < 32; ++k) {
      pos[k] = cnt(rng);
      neg[k] = cnt(rng);
    }
    const TaxelMap m(GridSpec::paper(), pz, pos, neg);
    std::uniform_real_distribution<double> ud(-0.1, 0.2), ut(0.0, 3.0);
    for (int n = 0; n < 2000; ++n) {
      const double d = ud(rng), t = ut(rng);
      const double a = m.activation(d, t);
      EXPECT_NEAR(a, m.activation_naive(d, t), 1e-12);
      EXPECT_GE(a, 0.0);
      EXPECT_LE(a, 1.0);
    }
  }
}

namespace {
void check_reference(const std::vector<TaxelMap::Count>& pos,
                     const std::vector<TaxelMap::Count>& neg, const std::array<double, 6>& ref) {
  const TaxelMap m(GridSpec::code(), ParzenSpec::code(), pos, neg);
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const auto [d, t] = pps_ref::kPoints[k];
    EXPECT_NEAR(m.activation(d, t), ref[k], 0.005) << "at (" << d << ", " << t << ")";
    EXPECT_NEAR(m.activation_naive(d, t), ref[k], 0.005);
  }
}
}  // namespace

// Self-contained copy of the validation against the iCub learned file (counts typed in).
TEST(PpsTaxelMap, ReferenceActivationTaxel3) {
  check_reference(pps_ref::kTaxel3Pos, pps_ref::kTaxel3Neg, pps_ref::kTaxel3Act);
}

TEST(PpsTaxelMap, ReferenceActivationTaxel101) {
  check_reference(pps_ref::kTaxel101Pos, pps_ref::kTaxel101Neg, pps_ref::kTaxel101Act);
}
