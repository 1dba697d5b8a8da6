// Noise schedule presets: the paper's and the released code's values and their evolution.
#include <gtest/gtest.h>

#include "somasim/body_schema/noise_schedule.hpp"
#include "somasim/error.hpp"

namespace somasim::body_schema {
namespace {

TEST(NoiseSchedule, PaperDecaysByPointEightToTheFloor) {
  const NoiseSchedule s = noise_schedule_preset("paper");
  EXPECT_DOUBLE_EQ(s.initial_sigma_deg, 5.0);
  double sigma = s.step_sigma_deg;
  EXPECT_DOUBLE_EQ(sigma, 4.0);
  sigma = s.next_sigma(sigma, true);
  EXPECT_DOUBLE_EQ(sigma, 3.2);
  sigma = s.next_sigma(sigma, false);  // the paper decays whether or not it resampled
  EXPECT_DOUBLE_EQ(sigma, 2.56);
  for (int i = 0; i < 100; ++i) sigma = s.next_sigma(sigma, true);
  EXPECT_DOUBLE_EQ(sigma, 0.08);
  EXPECT_EQ(s.resample_threshold, 0.0);
  EXPECT_FALSE(s.reset_particle_zero);
}

TEST(NoiseSchedule, Code2016ShrinksAfterResamplingGrowsOtherwiseWithinBounds) {
  const NoiseSchedule s = noise_schedule_preset("code2016");
  EXPECT_DOUBLE_EQ(s.initial_sigma_deg, 3.5);
  EXPECT_DOUBLE_EQ(s.step_sigma_deg, 3.0);
  EXPECT_DOUBLE_EQ(s.next_sigma(3.0, true), 2.55);
  EXPECT_DOUBLE_EQ(s.next_sigma(3.0, false), 3.45);
  EXPECT_DOUBLE_EQ(s.next_sigma(3.2, false), 3.5);
  EXPECT_DOUBLE_EQ(s.next_sigma(0.045, true), 0.04);
  EXPECT_DOUBLE_EQ(s.resample_threshold, 0.55);
  EXPECT_FALSE(s.reset_particle_zero);
}

TEST(NoiseSchedule, Code2017GrowsFasterAndKeepsTheNominalParticle) {
  const NoiseSchedule s = noise_schedule_preset("code2017");
  EXPECT_DOUBLE_EQ(s.next_sigma(2.0, false), 2.4);
  EXPECT_DOUBLE_EQ(s.next_sigma(2.0, true), 1.7);
  EXPECT_TRUE(s.reset_particle_zero);
}

TEST(NoiseSchedule, UnknownPresetNamesTheChoices) {
  try {
    noise_schedule_preset("fast");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown noise schedule 'fast' (expected paper, code2016 or code2017)");
  }
}

}  // namespace
}  // namespace somasim::body_schema
