// The fix window: the slope of the least-squares line through a track's last fixes and the rate
// its radius changes at, over generated straight and turning tracks, and the inputs it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>
#include <stdexcept>

#include "somasim/error.hpp"
#include "somasim/vision/fix_window.hpp"

using somasim::vision::FixWindow;

namespace {

Eigen::Vector3d random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

}  // namespace

// Fixes on a straight line at uneven times (frames dropped) give its velocity exactly, whatever
// the capacity; fewer than two fixes give zero.
TEST(FixWindow, AStraightTracksVelocityIsItsSlope) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> gap(0.02, 0.15);
  for (int trial = 0; trial < 50; ++trial) {
    const int capacity = 2 + trial % 7;
    FixWindow window(capacity);
    EXPECT_EQ(window.velocity(), Eigen::Vector3d::Zero());
    const Eigen::Vector3d start = random_vector(rng, 0.5), velocity = random_vector(rng, 0.4);
    double t = gap(rng);
    for (int k = 0; k < capacity + 3; ++k, t += gap(rng)) {
      window.add(t, start + t * velocity);
      const double error =
          window.size() == 1 ? window.velocity().norm() : (window.velocity() - velocity).norm();
      EXPECT_LT(error, 1e-9) << trial;
    }
    EXPECT_TRUE(window.full());
    EXPECT_EQ(window.size(), capacity);
    window.clear();
    EXPECT_EQ(window.size(), 0);
  }
}

// A track that turns: once the window holds only fixes after the turn, its slope is the new
// velocity; while it straddles the turn, it lies between the two.
TEST(FixWindow, OnlyTheLastFixesCount) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    FixWindow window(5);
    const Eigen::Vector3d before = random_vector(rng, 0.3), after = -before;
    Eigen::Vector3d p = random_vector(rng, 0.5);
    for (int k = 0; k < 10; ++k) window.add(0.05 * k, p += 0.05 * before);
    EXPECT_LT((window.velocity() - before).norm(), 1e-9);
    window.add(0.5, p += 0.05 * after);
    const double along = window.velocity().dot(before) / before.squaredNorm();
    EXPECT_GT(along, -1.0);
    EXPECT_LT(along, 1.0);
    for (int k = 11; k < 16; ++k) window.add(0.05 * k, p += 0.05 * after);
    EXPECT_LT((window.velocity() - after).norm(), 1e-9) << trial;
  }
}

// Noisy fixes of a still object: the slope's spread falls as the window grows (the least-squares
// slope's σ is the position σ √(12 / (n (n² − 1))) / frame interval).
TEST(FixWindow, TheSlopeOfNoisyFixesHasTheLeastSquaresSpread) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (const int n : {3, 5, 9}) {
    double sum_sq = 0.0;
    constexpr int kTrials = 4000;
    for (int trial = 0; trial < kTrials; ++trial) {
      FixWindow window(n);
      for (int k = 0; k < n; ++k) window.add(0.05 * k, Eigen::Vector3d(noise(rng), 0.0, 0.0));
      sum_sq += window.velocity().x() * window.velocity().x();
    }
    const double expected = 0.005 * std::sqrt(12.0 / (n * (n * n - 1.0))) / 0.05;
    EXPECT_NEAR(std::sqrt(sum_sq / kTrials), expected, 0.05 * expected) << n;
  }
}

// Radii on a straight line at uneven times: the rate is the line's slope over the held fixes'
// mean radius, whatever the capacity and sign; a constant radius, an unknown one (0) and a
// single fix read 0.
TEST(FixWindow, TheRadiusRateIsTheSlopeOverTheMeanRadius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> gap(0.02, 0.15), radius(0.005, 0.1), rate(-2.0, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int capacity = 2 + trial % 7;
    const double r0 = radius(rng), slope = rate(rng) * r0;
    FixWindow window(capacity), constant(capacity), unknown(capacity);
    double t = 0.0;
    std::deque<double> held;
    for (int k = 0; k < capacity + 3; ++k, t += gap(rng)) {
      const double r = std::max(r0 + slope * t, 1e-4);
      if (r != r0 + slope * t) break;  // a shrinking radius stays positive
      window.add(t, random_vector(rng, 0.5), r);
      constant.add(t, random_vector(rng, 0.5), r0);
      unknown.add(t, random_vector(rng, 0.5));
      held.push_back(r);
      if (static_cast<int>(held.size()) > capacity) held.pop_front();
      double mean = 0.0;
      for (const double h : held) mean += h / static_cast<double>(held.size());
      const double expected = held.size() < 2 ? 0.0 : std::abs(slope) / mean;
      EXPECT_NEAR(window.radius_rate(), expected, 1e-9 * (1.0 + expected)) << trial;
      EXPECT_NEAR(constant.radius_rate(), 0.0, 1e-9) << trial;
      EXPECT_EQ(unknown.radius_rate(), 0.0) << trial;
    }
  }
}

TEST(FixWindow, RefusesWhatCannotBeAWindow) {
  EXPECT_THROW(FixWindow(1), somasim::InputError);
  EXPECT_THROW(FixWindow(-3), somasim::InputError);
  FixWindow window(3);
  window.add(1.0, Eigen::Vector3d::Zero());
  EXPECT_THROW(window.add(0.5, Eigen::Vector3d::Zero()), std::logic_error);
  window.add(1.0, Eigen::Vector3d::Ones());  // two fixes at one time: no slope
  EXPECT_EQ(window.velocity(), Eigen::Vector3d::Zero());
}
