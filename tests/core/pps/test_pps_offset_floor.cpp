// Floor offset estimator: synthetic approach streams taught through the real learner
// (BodyPartLearner: receptive field, unsigned TTC, buffer, counts), ending at known points
// beside or along the normal of one taxel; the estimate is compared with the perceived D at
// contact (D = sign(p_z)|p| of the end point) and with the ridge end.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/offset_floor.hpp"
#include "somasim/pps/offset_ridge.hpp"

using namespace somasim::pps;

namespace {

// D over [-0.1, 0.2] m in 30 bins of 1 cm, TTC over [0, 3] s in 4; unsigned TTC, the released
// code's receptive field (mirrored below the skin), 3 s buffer: the pps_learn_objects settings.
LearnerParams fine_params() {
  LearnerParams p = LearnerParams::paper();
  p.grid.d_bins = 30;
  p.ttc = TtcDefinition::kUnsigned;
  p.rf = ReceptiveField::code();
  return p;
}

constexpr double kW = 0.01;  // D bin width [m]

// One taxel at the origin, normal +z (link frame = root frame).
struct Scene {
  BodyPartLearner learner{
      "patch",
      {TaxelInfo{0, TaxelPose{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()}}},
      fine_params()};
  std::mt19937 rng{7};
  double time = 0.0;

  // Approaches that end (and touch the taxel) at `end` [m], coming along `dir` (unit, toward
  // the skin) at 5-15 cm/s from 25 cm before the end, sampled every 50 ms with a random phase
  // (the last sample up to one period before the contact).
  void approach(const Eigen::Vector3d& end, const Eigen::Vector3d& dir) {
    std::uniform_real_distribution<double> speed_dist(0.05, 0.15), phase(0.0, 1.0);
    const double speed = speed_dist(rng), dt = 0.05;
    const double duration = 0.25 / speed;
    for (double to_contact = -duration + phase(rng) * dt; to_contact <= 0.0; to_contact += dt) {
      learner.push_stimulus(
          StimulusSample{time, Stimulus{end + dir * speed * to_contact, dir * speed, 0.0}});
      time += dt;
    }
    const std::vector<int> touched = {0};
    learner.on_contact(Eigen::Isometry3d::Identity(), touched);
    time += 10.0;  // the next approach starts with an empty buffer
  }

  const TaxelMap& map() {
    TaxelMap& m = learner.maps()[0];
    if (m.stale()) m.refresh();
    return m;
  }
};

// Perceived D at contact of an end point: sign(p_z)|p| (compute_d_ttc).
double perceived_d(const Eigen::Vector3d& end) {
  return compute_d_ttc(end, Eigen::Vector3d(0, 0, -1), TtcDefinition::kUnsigned).d;
}

// Unit direction toward the skin, `tilt` [rad] from -z, azimuth `azimuth` [rad].
Eigen::Vector3d inward(double tilt, double azimuth) {
  return Eigen::Vector3d(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth),
                         -std::cos(tilt));
}

constexpr int kApproaches = 12;

}  // namespace

// Pure normal offsets (the end on the normal, 2 cm outside, at, 2 cm behind the skin): counts
// are proportional to path length, so the floor is exact to a fraction of a bin and equals the
// ridge end.
TEST(PpsOffsetFloor, NormalOffsetsSubBinAndEqualToTheRidgeEnd) {
  for (double o : {-0.02, 0.0, 0.02}) {
    Scene s;
    const Eigen::Vector3d end(0, 0, o);
    for (int k = 0; k < kApproaches; ++k) s.approach(end, inward(0.0, 0.0));
    const auto floor = estimate_floor(s.map());
    const auto ridge = estimate_offset_ridge(s.map());
    ASSERT_TRUE(floor && ridge) << o;
    EXPECT_NEAR(floor->offset_m, perceived_d(end), 0.25 * kW) << o;
    EXPECT_NEAR(*ridge, perceived_d(end), 0.25 * kW) << o;
    EXPECT_NEAR(*estimate_offset_floor(s.map()), floor->offset_m, 1e-15);
  }
}

// Lateral offsets (the end on the tangent plane, 1-3 cm beside the taxel, paths along the
// normal): perceived D at contact = l. Samples bunch near D = l, so the floor is the lowest
// solid bin's edge, within a bin of l; the ridge end reads the distance along the normal,
// about l^2 / (2 D_ref): that is why there are two estimators.
TEST(PpsOffsetFloor, LateralOffsetsWithinABinWhereTheRidgeEndReadsTheNormalDistance) {
  for (double l : {0.01, 0.015, 0.02, 0.025, 0.03}) {
    Scene s;
    for (int k = 0; k < kApproaches; ++k) {
      const double azimuth = 2.0 * M_PI * k / kApproaches;  // all around the taxel
      s.approach(Eigen::Vector3d(l * std::cos(azimuth), l * std::sin(azimuth), 0.0),
                 inward(0.0, 0.0));
    }
    const auto floor = estimate_floor(s.map());
    const auto ridge = estimate_offset_ridge(s.map());
    ASSERT_TRUE(floor && ridge) << l;
    EXPECT_NEAR(perceived_d(Eigen::Vector3d(l, 0, 0)), l, 1e-15);
    EXPECT_LE(std::abs(floor->offset_m - l), kW) << l;
    EXPECT_GT(std::abs(*ridge - l), 0.5 * kW) << l;
  }
}

// Lateral and normal offsets together, from directions within 30 degrees of the normal: still
// within a bin of the perceived D at contact (a path tilted toward the taxel passes it closer
// than its end, down to cos(tilt) x l).
TEST(PpsOffsetFloor, TiltedApproachesAndMixedOffsetsWithinABin) {
  struct Case {
    double l, o;
  };
  for (const Case c : {Case{0.02, 0.0}, Case{0.015, 0.01}, Case{0.0, 0.015}, Case{0.01, -0.01}}) {
    Scene s;
    std::uniform_real_distribution<double> tilt(0.0, 30.0 * M_PI / 180.0), az(0.0, 2.0 * M_PI);
    double truth = 0.0;
    for (int k = 0; k < kApproaches; ++k) {
      const double a = 2.0 * M_PI * k / kApproaches;
      const Eigen::Vector3d end(c.l * std::cos(a), c.l * std::sin(a), c.o);
      truth += perceived_d(end) / kApproaches;
      const double t = tilt(s.rng), z = az(s.rng);
      s.approach(end, inward(t, z));
    }
    const auto floor = estimate_offset_floor(s.map());
    ASSERT_TRUE(floor.has_value()) << c.l << " " << c.o;
    EXPECT_LE(std::abs(*floor - truth), kW) << c.l << " " << c.o << ": " << *floor;
  }
}

// A few stray positive samples far below the ridge (e.g. of an approach that crossed the skin
// plane beside the taxel) are not "solid": the estimate ignores them unless min_fraction is
// lowered below their share.
TEST(PpsOffsetFloor, StraySamplesBelowTheRidgeAreIgnored) {
  Scene s;
  for (int k = 0; k < kApproaches; ++k) s.approach(Eigen::Vector3d(0, 0, 0.02), inward(0.0, 0.0));
  TaxelMap m = s.map();
  const double clean = *estimate_offset_floor(m);
  for (int k = 0; k < 3; ++k) m.add_sample(-0.005, 0.1, true, false);
  m.refresh();
  EXPECT_DOUBLE_EQ(*estimate_offset_floor(m), clean);
  FloorOptions loose;
  loose.min_fraction = 0.01;
  const auto fooled = estimate_floor(m, loose);
  ASSERT_TRUE(fooled.has_value());
  EXPECT_NEAR(fooled->edge_m, -0.01, 1e-9);
  EXPECT_LT(fooled->offset_m, 0.0);
}

TEST(PpsOffsetFloor, UndefinedWithoutARidgeAbove) {
  const GridSpec g = fine_params().grid;
  const TaxelMap empty(g, ParzenSpec::paper());
  EXPECT_FALSE(estimate_offset_floor(empty).has_value());
  // Positives only in the last D bin: nothing above it.
  TaxelMap top(g, ParzenSpec::paper());
  for (int n = 0; n < 50; ++n) top.add_sample(0.195, 1.0, true);
  EXPECT_FALSE(estimate_offset_floor(top).has_value());
  // A plateau of fewer than min_plateau_count counts per bin.
  TaxelMap thin(g, ParzenSpec::paper());
  for (int k = 0; k < 10; ++k) thin.add_sample(0.005 + 0.01 * k, 1.0, true);  // 1 per bin
  EXPECT_FALSE(estimate_offset_floor(thin).has_value());
  FloorOptions few;
  few.min_plateau_count = 1.0;
  EXPECT_NEAR(*estimate_offset_floor(thin, few), 0.0, 1e-9);
}

TEST(PpsOffsetFloor, WorksOnADistanceOnlyMap) {
  TaxelMap m(distance_only_grid(fine_params().grid), ParzenSpec::paper());
  for (int k = 0; k < 20; ++k)
    for (double d = 0.013 + 0.0004 * k; d <= 0.2; d += 0.004) m.add_sample(d, 0.5, true, false);
  m.refresh();
  EXPECT_NEAR(*estimate_offset_floor(m), 0.013 + 0.0002 * 19, 0.002);
}

TEST(PpsOffsetFloor, BadOptionsAreNamed) {
  const TaxelMap m(fine_params().grid, ParzenSpec::paper());
  FloorOptions o;
  o.min_fraction = 0.0;
  try {
    estimate_floor(m, o);
    FAIL() << "no error";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "floor offset estimator: min_fraction is 0.000000, expected a value in (0, 1]");
  }
  o = FloorOptions{};
  o.plateau_bins = 0;
  try {
    estimate_floor(m, o);
    FAIL() << "no error";
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "floor offset estimator: plateau_bins is 0, expected at least 1");
  }
}
