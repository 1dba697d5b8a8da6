#pragma once
/// @file
/// A 3-D Kalman filter (cv::KalmanFilter, double precision) of a point's position and velocity
/// from measured positions, with a constant-velocity or constant-acceleration motion model
/// (continuous white-noise acceleration or jerk). Positions [m], velocities [m/s], times [s];
/// any frame, as long as the measurements share it.
#include <memory>
#include <span>

#include <Eigen/Core>

#include "somasim/name_table.hpp"

namespace cv {
class KalmanFilter;
}

namespace somasim::vision {

enum class MotionModel {
  kConstantVelocity,      ///< state: position, velocity; white-noise acceleration
  kConstantAcceleration,  ///< state: position, velocity, acceleration; white-noise jerk
};
inline constexpr NamedValue<MotionModel> kMotionModelNames[] = {
    {MotionModel::kConstantVelocity, "constant_velocity"},
    {MotionModel::kConstantAcceleration, "constant_acceleration"}};
/// "constant_velocity", "constant_acceleration".
constexpr std::span<const NamedValue<MotionModel>> name_table(MotionModel) {
  return kMotionModelNames;
}

struct KalmanOptions {
  MotionModel model = MotionModel::kConstantVelocity;
  /// Spectral density of the white noise that drives the model: acceleration [m²/s³] for
  /// constant velocity, jerk [m²/s⁵] for constant acceleration.
  double process_noise = 1.0;
  double measurement_sigma_m = 0.002;       ///< σ of a measured position, per axis [m]
  double initial_velocity_sigma = 0.5;      ///< σ of the unknown velocity at the first fix [m/s]
  double initial_acceleration_sigma = 2.0;  ///< same for the acceleration [m/s²]

  /// The options a tracker plugin exposes, as a config block (somasim/config.hpp): the model,
  /// the process noise and the measurement σ; a plugin sets its own defaults by initialising
  /// the embedded member. The initial σ stay at the values above.
  template <class V>
  void visit(V& v) {
    v.field("motion_model", model).doc("the Kalman filter's motion model");
    v.field("process_noise", process_noise)
        .at_least(1e-9)
        .doc(
            "spectral density of the white acceleration [m²/s³] (constant_velocity) or jerk "
            "[m²/s⁵] (constant_acceleration) that drives the model");
    v.field("measurement_sigma", measurement_sigma_m)
        .unit("m")
        .at_least(1e-6)
        .doc("σ of a triangulated position per axis [m]");
  }
};

class KalmanTracker {
 public:
  /// Throws somasim::InputError naming the option for a noise or σ that is not > 0.
  explicit KalmanTracker(const KalmanOptions& options = {});
  ~KalmanTracker();
  KalmanTracker(KalmanTracker&&) noexcept;
  KalmanTracker& operator=(KalmanTracker&&) noexcept;

  /// The first measurement initialises the state (velocity 0); later ones predict by `dt_s`
  /// (> 0, else InputError) and correct.
  void update(const Eigen::Vector3d& measured_position, double dt_s);
  /// Predicts by `dt_s` without a measurement (a frame without the point); no-op before the
  /// first fix.
  void predict(double dt_s);
  /// Forgets the state (the next update() starts afresh).
  void reset();

  bool initialised() const { return initialised_; }
  Eigen::Vector3d position() const;  ///< [m]; zero before the first fix
  Eigen::Vector3d velocity() const;  ///< [m/s]; zero before the first fix
  /// Standard deviation of the position estimate along each axis [m].
  Eigen::Vector3d position_sigma() const;
  /// Standard deviation of the velocity estimate along each axis [m/s] (the model's: it falls
  /// with every fix from initial_velocity_sigma toward its steady state); zero before the first
  /// fix.
  Eigen::Vector3d velocity_sigma() const;

 private:
  void set_transition(double dt_s);
  KalmanOptions options_;
  int order_ = 2;  // 2: position, velocity; 3: + acceleration
  std::unique_ptr<cv::KalmanFilter> filter_;
  bool initialised_ = false;
};

}  // namespace somasim::vision
