// The trackers' latency metric: the least-squares lag of an estimate behind the truth.
#include <gtest/gtest.h>

#include <cmath>

#include "lag_estimate.hpp"

using somasim::plugins::LagEstimate;

// An estimate that is the truth 40 ms ago, on a circle at 0.2 m/s (the direction of motion
// turns, so the lag is not confused with a constant offset): τ = 0.04 s within the curvature's
// second-order error.
TEST(LagEstimate, AnEstimateDelayedByFortyMillisecondsGivesFortyMilliseconds) {
  LagEstimate lag(0.01);
  const double radius = 0.1, omega = 2.0, delay = 0.04;
  const auto at = [&](double t) {
    return Eigen::Vector3d(radius * std::cos(omega * t), radius * std::sin(omega * t), 0.0);
  };
  const auto velocity = [&](double t) {
    return Eigen::Vector3d(-radius * omega * std::sin(omega * t),
                           radius * omega * std::cos(omega * t), 0.0);
  };
  for (int k = 0; k < 200; ++k) {
    const double t = 0.05 * k;
    lag.add(at(t - delay) - at(t), velocity(t));
  }
  EXPECT_NEAR(lag.seconds(), delay, 1e-4);
}

TEST(LagEstimate, ATruthAtRestLeavesNoSampleAndALeadIsNegative) {
  LagEstimate lag(0.01);
  lag.add(Eigen::Vector3d(0.01, 0, 0), Eigen::Vector3d(0.005, 0, 0));  // slower than 1 cm/s
  EXPECT_EQ(lag.seconds(), 0.0);
  lag.add(Eigen::Vector3d(0.002, 0, 0), Eigen::Vector3d(0.1, 0, 0));  // 20 ms ahead
  EXPECT_NEAR(lag.seconds(), -0.02, 1e-12);
}
