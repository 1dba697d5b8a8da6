// The settling gate over generated tracks (runs of fixes whose radius rates are settled or not,
// new tracks among them) against a direct reading of its rule, and the settings it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "somasim/error.hpp"
#include "somasim/vision/settling_gate.hpp"

using somasim::vision::SettlingGate;

namespace {

struct Fix {
  int window_fixes;
  double radius_rate;
};

// The rule read directly off the whole history: settled when the window is full and none of the
// track's last `window` fixes (this one included) had a rate over `max` from three fixes on.
bool settled_by_rule(const std::vector<Fix>& track, double max, int window) {
  const Fix& now = track.back();
  if (now.window_fixes < window) return false;
  const int n = static_cast<int>(track.size());
  for (int k = std::max(0, n - window); k < n; ++k)
    if (track[k].window_fixes >= 3 && track[k].radius_rate > max) return false;
  return true;
}

}  // namespace

TEST(SettlingGate, AgreesWithItsRuleOverGeneratedTracks) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> rate(0.0, 2.0);
  std::uniform_int_distribution<int> length(1, 30), window(2, 8);
  int settled = 0, unsettled = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int w = window(rng);
    const double max = 0.5 + 0.1 * (trial % 10);
    SettlingGate gate(max, w);
    for (int t = 0; t < 6; ++t) {  // consecutive tracks through one gate
      std::vector<Fix> track;
      const int fixes = length(rng);
      const double spike_share = (trial + t) % 3 == 0 ? 0.0 : 0.15;
      std::bernoulli_distribution spike(spike_share);
      for (int k = 1; k <= fixes; ++k) {
        track.push_back({std::min(k, w), spike(rng) ? max + rate(rng) : max * rate(rng) / 2.0});
        const bool expected = settled_by_rule(track, max, w);
        EXPECT_EQ(gate.update(track.back().window_fixes, track.back().radius_rate), expected)
            << "trial " << trial << " track " << t << " fix " << k;
        (expected ? settled : unsettled)++;
      }
    }
  }
  EXPECT_GT(settled, 1000);
  EXPECT_GT(unsettled, 1000);
}

// A rate just over the bound at the fix that fills the window keeps the track unsettled for
// exactly `window` fixes; a rate read from two fixes never counts.
TEST(SettlingGate, AnUnsettledFixHoldsTheNextWindowMinusOne) {
  SettlingGate gate(1.0, 5);
  EXPECT_FALSE(gate.update(1, 0.0));
  EXPECT_FALSE(gate.update(2, 50.0));  // two fixes: no rate
  EXPECT_FALSE(gate.update(3, 0.0));
  EXPECT_FALSE(gate.update(4, 0.0));
  EXPECT_TRUE(gate.update(5, 0.0));
  EXPECT_FALSE(gate.update(5, 1.01));
  for (int k = 0; k < 4; ++k) EXPECT_FALSE(gate.update(5, 0.0)) << k;
  EXPECT_TRUE(gate.update(5, 0.0));
  EXPECT_TRUE(gate.update(5, 1.0));  // at the bound: settled
}

TEST(SettlingGate, RefusesSettingsThatCannotGate) {
  EXPECT_THROW(SettlingGate(0.0, 5), somasim::InputError);
  EXPECT_THROW(SettlingGate(-1.0, 5), somasim::InputError);
  EXPECT_THROW(SettlingGate(1.0, 1), somasim::InputError);
}
