#include <cmath>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/figures/ticks.hpp"

namespace fig = somasim::figures;

namespace {
void expect_ticks(double lo, double hi, int max_ticks, const std::vector<double>& expected) {
  const auto t = fig::nice_ticks(lo, hi, max_ticks);
  ASSERT_EQ(t.size(), expected.size()) << "[" << lo << ", " << hi << "]";
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], expected[i], 1e-12) << i;
}
}  // namespace

TEST(NiceTicks, UnitRangeUsesStepOfPointTwo) {
  expect_ticks(0, 1, 8, {0, 0.2, 0.4, 0.6, 0.8, 1.0});
}

TEST(NiceTicks, TtcRanges) {
  expect_ticks(0, 1.2, 8, {0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2});
  expect_ticks(0, 3, 8, {0, 0.5, 1, 1.5, 2, 2.5, 3});
}

TEST(NiceTicks, DistanceInCentimetresCrossesZero) {
  expect_ticks(-10, 20, 8, {-10, -5, 0, 5, 10, 15, 20});
  EXPECT_DOUBLE_EQ(fig::nice_step(-10, 20, 8), 5);
}

TEST(NiceTicks, OnlyTicksInsideTheRange) {
  expect_ticks(-0.043, 0.187, 6, {0, 0.05, 0.1, 0.15});
  expect_ticks(0.013, 0.97, 4, {0.2, 0.4, 0.6, 0.8});
}

TEST(NiceTicks, StepsAreOneTwoOrFiveTimesAPowerOfTen) {
  for (double span : {0.0037, 0.09, 1.0, 7.3, 42.0, 999.0, 12345.0}) {
    for (int n : {3, 5, 8, 10}) {
      const double step = fig::nice_step(0.1, 0.1 + span, n);
      const double mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
      EXPECT_TRUE(std::fabs(mant - 1) < 1e-9 || std::fabs(mant - 2) < 1e-9 ||
                  std::fabs(mant - 5) < 1e-9)
          << "span " << span << " n " << n << " step " << step;
      EXPECT_LE(fig::nice_ticks(0.1, 0.1 + span, n).size(), static_cast<std::size_t>(n));
    }
  }
}

TEST(NiceTicks, ZeroIsExactlyZero) {
  const auto t = fig::nice_ticks(-0.3, 0.3, 8);
  bool found = false;
  for (double v : t)
    if (v == 0.0) {
      found = true;
      EXPECT_FALSE(std::signbit(v));
    }
  EXPECT_TRUE(found);
}

TEST(NiceTicks, InvalidRangeThrowsInputError) {
  try {
    fig::nice_ticks(1, 1);
    FAIL() << "expected InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "nice_ticks: range [1, 1] is invalid; expected finite lo < hi");
  }
  EXPECT_THROW(fig::nice_ticks(0, std::nan("")), somasim::InputError);
  try {
    fig::nice_ticks(0, 1, 1);
    FAIL() << "expected InputError";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "nice_ticks: max_ticks is 1; expected at least 2");
  }
}

TEST(FormatTick, DecimalsFollowTheStep) {
  EXPECT_EQ(fig::format_tick(0.2, 0.2), "0.2");
  EXPECT_EQ(fig::format_tick(1.0, 0.2), "1.0");
  EXPECT_EQ(fig::format_tick(0.05, 0.05), "0.05");
  EXPECT_EQ(fig::format_tick(-10, 5), "-10");
  EXPECT_EQ(fig::format_tick(1500, 500), "1500");
  EXPECT_EQ(fig::format_tick(0.25, 0.25), "0.25");
}

TEST(FormatTick, NeverNegativeZero) {
  EXPECT_EQ(fig::format_tick(-0.0, 0.5), "0.0");
  EXPECT_EQ(fig::format_tick(-1e-17, 0.1), "0.0");
  EXPECT_EQ(fig::format_tick(-0.0, 5), "0");
}
