#include <gtest/gtest.h>

#include "somasim/pps/stimulus_buffer.hpp"

using namespace somasim::pps;

namespace {
StimulusSample at(double t) {
  return StimulusSample{t, Stimulus{}};
}
}  // namespace

TEST(PpsStimulusBuffer, CodeHorizonKeeps80SamplesAt50ms) {
  StimulusBuffer b(BufferSpec::code());
  for (int i = 0; i <= 200; ++i) b.push(at(i * 0.05));
  EXPECT_EQ(b.size(), 80u);
  EXPECT_NEAR(b.samples().front().time, 10.0 - 3.95, 1e-9);
}

TEST(PpsStimulusBuffer, PaperHorizonKeeps60Samples) {
  StimulusBuffer b(BufferSpec::paper());
  for (int i = 0; i <= 200; ++i) b.push(at(i * 0.05));
  EXPECT_EQ(b.size(), 60u);
}

TEST(PpsStimulusBuffer, UnlimitedHorizon) {
  StimulusBuffer b(BufferSpec{0.0, 2.0});
  for (int i = 0; i < 500; ++i) b.push(at(i * 0.05));
  EXPECT_EQ(b.size(), 500u);
}

TEST(PpsStimulusBuffer, ForgetsAfterTwoSecondsWithoutStimulus) {
  StimulusBuffer b(BufferSpec::code());
  for (int i = 0; i < 10; ++i) b.push(at(i * 0.05));
  b.update(0.45 + 2.0);
  EXPECT_EQ(b.size(), 10u);
  b.update(0.45 + 2.01);
  EXPECT_TRUE(b.empty());
  for (int i = 0; i < 10; ++i) b.push(at(10 + i * 0.05));
  b.push(at(10.45 + 2.5));  // gap > 2 s: the old samples are forgotten
  EXPECT_EQ(b.size(), 1u);
}
