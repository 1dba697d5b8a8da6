// Profiles (values, derivatives against finite differences) and multi-joint trajectories.
#include <gtest/gtest.h>

#include "somasim/control/trajectory.hpp"
#include "somasim/error.hpp"

using somasim::control::JointTrajectory;
using somasim::control::Profile;
using somasim::control::sample_profile;

TEST(ControlProfile, EndsAndMidpoint) {
  for (Profile p : {Profile::kLinear, Profile::kMinimumJerk}) {
    EXPECT_EQ(sample_profile(p, 0.0).s, 0.0);
    EXPECT_EQ(sample_profile(p, 1.0).s, 1.0);
    EXPECT_NEAR(sample_profile(p, 0.5).s, 0.5, 1e-15);
    EXPECT_EQ(sample_profile(p, -1.0).s, 0.0);  // clamped
    EXPECT_EQ(sample_profile(p, 2.0).s, 1.0);
  }
  EXPECT_EQ(sample_profile(Profile::kMinimumJerk, 0.0).ds, 0.0);
  EXPECT_EQ(sample_profile(Profile::kMinimumJerk, 1.0).ds, 0.0);
  EXPECT_NEAR(sample_profile(Profile::kMinimumJerk, 0.5).ds, 1.875, 1e-15);
}

TEST(ControlProfile, DerivativeMatchesFiniteDifferences) {
  const double h = 1e-6;
  for (Profile p : {Profile::kLinear, Profile::kMinimumJerk})
    for (double tau = 0.05; tau < 1.0; tau += 0.1)
      EXPECT_NEAR(sample_profile(p, tau).ds,
                  (sample_profile(p, tau + h).s - sample_profile(p, tau - h).s) / (2 * h), 1e-8);
}

TEST(ControlTrajectory, WaypointsTimesAndHolding) {
  JointTrajectory t(Profile::kMinimumJerk, 2.0, Eigen::Vector2d(0, 1),
                    {{Eigen::Vector2d(1, 1), 1.0}, {Eigen::Vector2d(1, -1), 2.0}});
  EXPECT_EQ(t.start_time(), 2.0);
  EXPECT_EQ(t.end_time(), 5.0);
  Eigen::VectorXd q(2), qd(2);
  t.sample(1.0, q, qd);  // before the start: holds the start
  EXPECT_EQ(q, Eigen::Vector2d(0, 1));
  t.sample(2.5, q, qd);
  EXPECT_NEAR(q[0], 0.5, 1e-15);
  EXPECT_NEAR(qd[0], 1.875, 1e-15);
  EXPECT_EQ(qd[1], 0.0);
  t.sample(3.0, q, qd);
  EXPECT_NEAR(q[0], 1.0, 1e-15);
  EXPECT_NEAR(qd.norm(), 0.0, 1e-15);
  t.sample(4.0, q, qd);
  EXPECT_NEAR(q[1], 0.0, 1e-15);
  EXPECT_NEAR(qd[1], -2.0 * 1.875 / 2.0, 1e-15);
  EXPECT_EQ(t.segment_at(4.0), 1);
  EXPECT_FALSE(t.finished(4.999));
  EXPECT_TRUE(t.finished(5.0));
  t.sample(9.0, q, qd);
  EXPECT_EQ(q, Eigen::Vector2d(1, -1));
  EXPECT_EQ(qd, Eigen::Vector2d(0, 0));
}

TEST(ControlTrajectory, BadWaypointsAreInputErrors) {
  try {
    JointTrajectory(Profile::kLinear, 0.0, Eigen::Vector2d(0, 0),
                    {{Eigen::Vector3d(1, 1, 1), 1.0}});
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "trajectory waypoint 0: expected 2 joint values, got 3");
  }
  try {
    JointTrajectory(Profile::kLinear, 0.0, Eigen::Vector2d(0, 0), {{Eigen::Vector2d(1, 1), 0.0}});
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "trajectory waypoint 0: expected a positive duration, got 0.000000");
  }
  try {
    somasim::control::parse_profile("min_jerk");
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "unknown trajectory profile 'min_jerk'; expected 'linear' or 'minimum_jerk'");
  }
}
