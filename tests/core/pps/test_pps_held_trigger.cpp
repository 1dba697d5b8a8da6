// The held trigger: over generated above/below sequences at a controller's tick, it holds
// exactly where the activation has been above the threshold without a break for hold_s; a
// crossing shorter than hold_s never triggers; a tick whose activation is sure triggers at once.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <vector>

#include "somasim/error.hpp"
#include "somasim/pps/held_trigger.hpp"

using somasim::pps::HeldTrigger;

namespace {

constexpr double kTick = 0.01;  // [s]: a controller at 100 Hz

// Runs of above/below ticks of random lengths (the activation a camera frame of 5 ticks holds).
std::vector<bool> random_crossings(std::mt19937& rng, int ticks) {
  std::uniform_int_distribution<int> run(1, 4);
  std::bernoulli_distribution above(0.5);
  std::vector<bool> out;
  while (static_cast<int>(out.size()) < ticks) {
    const bool a = above(rng);
    for (int k = run(rng) * 5; k > 0 && static_cast<int>(out.size()) < ticks; --k) out.push_back(a);
  }
  return out;
}

}  // namespace

TEST(HeldTrigger, HoldsWhereTheActivationHasStayedAboveForTheHoldTime) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 200; ++trial) {
    const int hold_ticks = trial % 12;
    HeldTrigger trigger(hold_ticks * kTick);
    const std::vector<bool> above = random_crossings(rng, 400);
    int run = 0;  // ticks above so far in the current crossing, this one included
    for (std::size_t k = 0; k < above.size(); ++k) {
      run = above[k] ? run + 1 : 0;
      const bool expected = above[k] && run - 1 >= hold_ticks;
      ASSERT_EQ(trigger.update(static_cast<double>(k) * kTick, above[k]), expected)
          << "trial " << trial << ", tick " << k << ", hold " << hold_ticks;
    }
  }
}

// One camera frame at 20 Hz is 5 ticks: with a hold of 0.05 s it never triggers, two frames do
// at their sixth tick; without a hold the first tick triggers.
TEST(HeldTrigger, AOneFrameTransientMovesNothing) {
  for (const int frames : {1, 2, 3}) {
    HeldTrigger held(0.05), at_once(0.0);
    int first_held = -1, first_at_once = -1;
    for (int k = 0; k < 40; ++k) {
      const bool above = k >= 10 && k < 10 + 5 * frames;
      if (held.update(k * kTick, above) && first_held < 0) first_held = k;
      if (at_once.update(k * kTick, above) && first_at_once < 0) first_at_once = k;
    }
    EXPECT_EQ(first_at_once, 10) << frames;
    EXPECT_EQ(first_held, frames == 1 ? -1 : 15) << frames;
  }
}

// Generated crossings whose ticks are now and then sure (far above the threshold): a sure tick
// triggers at once, whatever the crossing's age; the others wait the hold as before, and a sure
// tick does not shorten the hold of the ticks after it.
TEST(HeldTrigger, ASureCrossingTriggersWithoutTheHold) {
  std::mt19937 rng(29);
  std::bernoulli_distribution sure_draw(0.2);
  for (int trial = 0; trial < 200; ++trial) {
    const int hold_ticks = 1 + trial % 10;
    HeldTrigger trigger(hold_ticks * kTick);
    const std::vector<bool> above = random_crossings(rng, 400);
    int run = 0;
    for (std::size_t k = 0; k < above.size(); ++k) {
      run = above[k] ? run + 1 : 0;
      const bool sure = above[k] && sure_draw(rng);
      const bool expected = sure || (above[k] && run - 1 >= hold_ticks);
      ASSERT_EQ(trigger.update(static_cast<double>(k) * kTick, above[k], sure), expected)
          << "trial " << trial << ", tick " << k << ", hold " << hold_ticks;
    }
  }
}

TEST(HeldTrigger, ResetForgetsTheCrossing) {
  HeldTrigger trigger(0.05);
  for (int k = 0; k < 4; ++k) EXPECT_FALSE(trigger.update(k * kTick, true));
  trigger.reset();
  for (int k = 4; k < 9; ++k) EXPECT_FALSE(trigger.update(k * kTick, true)) << k;
  EXPECT_TRUE(trigger.update(9 * kTick, true));
}

TEST(HeldTrigger, RefusesAHoldTimeThatIsNotOne) {
  EXPECT_THROW(HeldTrigger(-0.01), somasim::InputError);
  EXPECT_THROW(HeldTrigger(std::numeric_limits<double>::quiet_NaN()), somasim::InputError);
  EXPECT_THROW(HeldTrigger(std::numeric_limits<double>::infinity()), somasim::InputError);
}
