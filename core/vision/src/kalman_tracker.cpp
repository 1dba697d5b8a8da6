#include "somasim/vision/kalman_tracker.hpp"

#include <cmath>

#include <fmt/format.h>

#include <opencv2/video/tracking.hpp>

#include "somasim/error.hpp"

namespace somasim::vision {
namespace {

void check_positive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw InputError(fmt::format("Kalman tracker: {}: expected > 0, got {}", name, value));
}

// Per-axis blocks of the discretised white-noise models: state index = axis + 3 * derivative.
double& at(cv::Mat& m, int i, int j) {
  return m.at<double>(i, j);
}

}  // namespace

KalmanTracker::KalmanTracker(const KalmanOptions& options)
    : options_(options),
      order_(options.model == MotionModel::kConstantVelocity ? 2 : 3),
      filter_(std::make_unique<cv::KalmanFilter>(3 * order_, 3, 0, CV_64F)) {
  check_positive(options.process_noise, "process_noise");
  check_positive(options.measurement_sigma_m, "measurement_sigma_m");
  check_positive(options.initial_velocity_sigma, "initial_velocity_sigma");
  check_positive(options.initial_acceleration_sigma, "initial_acceleration_sigma");
  filter_->measurementMatrix = cv::Mat::zeros(3, 3 * order_, CV_64F);
  for (int a = 0; a < 3; ++a) at(filter_->measurementMatrix, a, a) = 1.0;
  filter_->measurementNoiseCov =
      cv::Mat::eye(3, 3, CV_64F) * (options.measurement_sigma_m * options.measurement_sigma_m);
}

KalmanTracker::~KalmanTracker() = default;
KalmanTracker::KalmanTracker(KalmanTracker&&) noexcept = default;
KalmanTracker& KalmanTracker::operator=(KalmanTracker&&) noexcept = default;

void KalmanTracker::set_transition(double dt) {
  const int n = 3 * order_;
  cv::Mat& f = filter_->transitionMatrix;
  cv::Mat& q = filter_->processNoiseCov;
  f = cv::Mat::eye(n, n, CV_64F);
  q = cv::Mat::zeros(n, n, CV_64F);
  const double s = options_.process_noise;
  // Continuous white noise on the highest derivative, discretised over dt (per axis).
  double block[3][3] = {};
  if (order_ == 2) {
    const double b[2][2] = {{dt * dt * dt / 3, dt * dt / 2}, {dt * dt / 2, dt}};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) block[i][j] = s * b[i][j];
  } else {
    const double d2 = dt * dt, d3 = d2 * dt, d4 = d3 * dt, d5 = d4 * dt;
    const double b[3][3] = {
        {d5 / 20, d4 / 8, d3 / 6}, {d4 / 8, d3 / 3, d2 / 2}, {d3 / 6, d2 / 2, dt}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) block[i][j] = s * b[i][j];
  }
  for (int a = 0; a < 3; ++a) {
    at(f, a, a + 3) = dt;
    if (order_ == 3) {
      at(f, a, a + 6) = 0.5 * dt * dt;
      at(f, a + 3, a + 6) = dt;
    }
    for (int i = 0; i < order_; ++i)
      for (int j = 0; j < order_; ++j) at(q, a + 3 * i, a + 3 * j) = block[i][j];
  }
}

void KalmanTracker::update(const Eigen::Vector3d& measured, double dt_s) {
  if (!initialised_) {
    const int n = 3 * order_;
    filter_->statePost = cv::Mat::zeros(n, 1, CV_64F);
    filter_->errorCovPost = cv::Mat::zeros(n, n, CV_64F);
    const double sigmas[3] = {options_.measurement_sigma_m, options_.initial_velocity_sigma,
                              options_.initial_acceleration_sigma};
    for (int a = 0; a < 3; ++a) {
      at(filter_->statePost, a, 0) = measured[a];
      for (int k = 0; k < order_; ++k)
        at(filter_->errorCovPost, a + 3 * k, a + 3 * k) = sigmas[k] * sigmas[k];
    }
    filter_->statePre = filter_->statePost.clone();
    filter_->errorCovPre = filter_->errorCovPost.clone();
    initialised_ = true;
    return;
  }
  check_positive(dt_s, "dt_s");
  set_transition(dt_s);
  filter_->predict();
  const cv::Mat z = (cv::Mat_<double>(3, 1) << measured.x(), measured.y(), measured.z());
  filter_->correct(z);
}

void KalmanTracker::predict(double dt_s) {
  if (!initialised_) return;
  check_positive(dt_s, "dt_s");
  set_transition(dt_s);
  filter_->predict();
  // No measurement: the prediction is the estimate.
  filter_->statePre.copyTo(filter_->statePost);
  filter_->errorCovPre.copyTo(filter_->errorCovPost);
}

void KalmanTracker::reset() {
  initialised_ = false;
}

Eigen::Vector3d KalmanTracker::position() const {
  if (!initialised_) return Eigen::Vector3d::Zero();
  const cv::Mat& x = filter_->statePost;
  return {x.at<double>(0), x.at<double>(1), x.at<double>(2)};
}

Eigen::Vector3d KalmanTracker::velocity() const {
  if (!initialised_) return Eigen::Vector3d::Zero();
  const cv::Mat& x = filter_->statePost;
  return {x.at<double>(3), x.at<double>(4), x.at<double>(5)};
}

Eigen::Vector3d KalmanTracker::velocity_sigma() const {
  if (!initialised_) return Eigen::Vector3d::Zero();
  const cv::Mat& p = filter_->errorCovPost;
  return {std::sqrt(p.at<double>(3, 3)), std::sqrt(p.at<double>(4, 4)),
          std::sqrt(p.at<double>(5, 5))};
}

Eigen::Vector3d KalmanTracker::position_sigma() const {
  if (!initialised_) return Eigen::Vector3d::Zero();
  const cv::Mat& p = filter_->errorCovPost;
  return {std::sqrt(p.at<double>(0, 0)), std::sqrt(p.at<double>(1, 1)),
          std::sqrt(p.at<double>(2, 2))};
}

}  // namespace somasim::vision
