// The Kalman tracker: a point moving at constant velocity, measured with noise, and frames
// without a measurement; both motion models.
#include <gtest/gtest.h>

#include <random>

#include "somasim/error.hpp"
#include "somasim/vision/kalman_tracker.hpp"

namespace vision = somasim::vision;

namespace {

struct Errors {
  double position = 0.0, velocity = 0.0;
};

// 100 frames at 30 Hz of a point at 0.2 m/s, measured with σ = 2 mm; errors at the end.
Errors track(vision::MotionModel model, double measurement_noise_m) {
  vision::KalmanOptions options;
  options.model = model;
  options.measurement_sigma_m = 0.002;
  options.process_noise = model == vision::MotionModel::kConstantVelocity ? 0.05 : 0.5;
  vision::KalmanTracker kf(options);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, measurement_noise_m);
  const Eigen::Vector3d p0(0.3, -0.1, 0.2), v(0.2, 0.1, -0.05);
  const double dt = 1.0 / 30;
  Eigen::Vector3d p = p0;
  for (int k = 0; k < 100; ++k) {
    p = p0 + k * dt * v;
    kf.update(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)), dt);
  }
  return {(kf.position() - p).norm(), (kf.velocity() - v).norm()};
}

}  // namespace

TEST(KalmanTracker, ExactMeasurementsOfConstantVelocity) {
  for (const auto model :
       {vision::MotionModel::kConstantVelocity, vision::MotionModel::kConstantAcceleration}) {
    const Errors e = track(model, 0.0);
    EXPECT_LT(e.position, 1e-4);
    EXPECT_LT(e.velocity, 0.005);  // of 0.23 m/s
  }
}

TEST(KalmanTracker, NoisyMeasurementsOfConstantVelocity) {
  for (const auto model :
       {vision::MotionModel::kConstantVelocity, vision::MotionModel::kConstantAcceleration}) {
    const Errors e = track(model, 0.002);
    EXPECT_LT(e.position, 0.003);  // the filter smooths: below the raw 3.5 mm (3-D σ)
    EXPECT_LT(e.velocity, 0.04);
  }
}

TEST(KalmanTracker, PredictsThroughFramesWithoutMeasurement) {
  vision::KalmanTracker kf;
  EXPECT_FALSE(kf.initialised());
  kf.predict(0.1);  // nothing yet: no-op
  EXPECT_EQ(kf.position(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d v(0.1, 0, 0);
  const double dt = 0.02;
  for (int k = 0; k < 50; ++k) kf.update(k * dt * v, dt);
  const double sigma_before = kf.position_sigma().x();
  for (int k = 50; k < 60; ++k) kf.predict(dt);
  EXPECT_NEAR(kf.position().x(), 59 * dt * v.x(), 0.001);  // carried on at the same velocity
  EXPECT_GT(kf.position_sigma().x(), sigma_before);        // less sure without measurements
  kf.reset();
  EXPECT_FALSE(kf.initialised());
  kf.update(Eigen::Vector3d(1, 2, 3), dt);
  EXPECT_EQ(kf.position(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(kf.velocity(), Eigen::Vector3d::Zero());
}

// The velocity's σ starts at initial_velocity_sigma with the first fix, falls with every fix
// toward a steady state (both models) and grows again through frames without one.
TEST(KalmanTracker, TheVelocitysSigmaFallsWithEveryFix) {
  for (const auto model :
       {vision::MotionModel::kConstantVelocity, vision::MotionModel::kConstantAcceleration}) {
    vision::KalmanOptions options;
    options.model = model;
    options.measurement_sigma_m = 0.005;
    vision::KalmanTracker kf(options);
    EXPECT_EQ(kf.velocity_sigma(), Eigen::Vector3d::Zero());
    const double dt = 0.05;
    kf.update(Eigen::Vector3d::Zero(), dt);
    EXPECT_NEAR(kf.velocity_sigma().x(), options.initial_velocity_sigma, 1e-12);
    double last = kf.velocity_sigma().maxCoeff();
    for (int k = 1; k < 12; ++k) {
      kf.update(Eigen::Vector3d(0.01 * k, 0, 0), dt);
      const double now = kf.velocity_sigma().maxCoeff();
      EXPECT_LT(now, last) << "fix " << k + 1;
      last = now;
    }
    // Steady state with the default noise: about 0.05 m/s (jerk), 0.18 m/s (acceleration).
    EXPECT_LT(last, model == vision::MotionModel::kConstantAcceleration ? 0.06 : 0.2);
    kf.predict(dt);
    kf.predict(dt);
    EXPECT_GT(kf.velocity_sigma().maxCoeff(), last);
  }
}

TEST(KalmanTracker, BadOptionsAreClearErrors) {
  vision::KalmanOptions bad;
  bad.measurement_sigma_m = 0;
  try {
    vision::KalmanTracker kf(bad);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "Kalman tracker: measurement_sigma_m: expected > 0, got 0");
  }
  vision::KalmanTracker kf;
  kf.update(Eigen::Vector3d::Zero(), 0.1);
  try {
    kf.update(Eigen::Vector3d::Zero(), 0.0);
    FAIL();
  } catch (const somasim::InputError& e) {
    EXPECT_STREQ(e.what(), "Kalman tracker: dt_s: expected > 0, got 0");
  }
}

// A point under constant acceleration (a = (0.5, -0.3, 0.2) m/s²), exactly measured at 30 Hz
// for 3 s: the constant-acceleration model's velocity converges to the truth; the
// constant-velocity model's lags behind (its velocity error stays near a × its lag).
TEST(KalmanTracker, ConstantAccelerationModelFollowsAnAcceleratingPoint) {
  const Eigen::Vector3d p0(0.3, 0.1, 0.2), v0(-0.1, 0.05, 0), a(0.5, -0.3, 0.2);
  const double dt = 1.0 / 30;
  const auto errors = [&](vision::MotionModel model, double process_noise) {
    vision::KalmanOptions options;
    options.model = model;
    options.process_noise = process_noise;
    options.measurement_sigma_m = 0.001;
    vision::KalmanTracker kf(options);
    Eigen::Vector3d v = v0;
    for (int k = 0; k <= 90; ++k) {
      const double t = k * dt;
      kf.update(p0 + v0 * t + 0.5 * a * t * t, dt);
      v = v0 + a * t;
    }
    return (kf.velocity() - v).norm();
  };
  const double ca = errors(vision::MotionModel::kConstantAcceleration, 0.5);
  const double cv = errors(vision::MotionModel::kConstantVelocity, 0.05);
  EXPECT_LT(ca, 0.002);  // of 0.4 m/s at the end
  EXPECT_GT(cv, 5 * ca);
}
