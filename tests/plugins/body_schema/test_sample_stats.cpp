// The body-schema reports' sample statistics: mean and sample standard deviation (n − 1), the
// median (the upper middle of an even count), NaN for no samples.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sample_stats.hpp"

using somasim::plugins::mean_sd;
using somasim::plugins::median;

TEST(SampleStats, MeanAndSampleStandardDeviation) {
  const auto s = mean_sd({2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0});
  EXPECT_EQ(s.n, 8);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_DOUBLE_EQ(s.sd, std::sqrt(32.0 / 7.0));
  const auto one = mean_sd({3.5});
  EXPECT_EQ(one.n, 1);
  EXPECT_DOUBLE_EQ(one.mean, 3.5);
  EXPECT_EQ(one.sd, 0.0);
  const auto none = mean_sd({});
  EXPECT_EQ(none.n, 0);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.sd));
}

TEST(SampleStats, Median) {
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 3.0);  // the upper middle
  EXPECT_TRUE(std::isnan(median({})));
}
