#pragma once
// How far a tracked position lags behind the truth, for the trackers' latency_s metric.
#include <Eigen/Core>

namespace somasim::plugins {

/// The lag τ [s] of an estimate behind the truth: p_est(t) ≈ p(t − τ) ≈ p(t) − τ v(t), so the
/// least-squares τ over the samples is −Σ e·v / Σ |v|², e = p_est − p [m], v the true velocity
/// [m/s]. Samples where the truth moves slower than `min_speed` are left out (there the error is
/// noise, not lag).
class LagEstimate {
 public:
  explicit LagEstimate(double min_speed = 0.01) : min_speed_(min_speed) {}
  void add(const Eigen::Vector3d& error, const Eigen::Vector3d& true_velocity) {
    if (true_velocity.norm() <= min_speed_) return;
    numerator_ -= error.dot(true_velocity);
    denominator_ += true_velocity.squaredNorm();
  }
  /// [s]; 0 without samples.
  double seconds() const { return denominator_ > 0 ? numerator_ / denominator_ : 0.0; }

 private:
  double min_speed_;
  double numerator_ = 0.0, denominator_ = 0.0;
};

}  // namespace somasim::plugins
