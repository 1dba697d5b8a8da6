#pragma once
/// @file
/// Joint-space trajectories through waypoints with a linear or minimum-jerk time profile.
///
/// Units: positions [rad] (prismatic joints [m]), velocities [rad/s], times [s]. A trajectory
/// covers any subset of the robot's joints; its vectors are in the caller's joint order.
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/name_table.hpp"

namespace somasim::control {

/// Time profile of one segment.
///  - kLinear: constant velocity Δq/T (velocity jumps at the segment ends);
///  - kMinimumJerk: s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ (Flash & Hogan 1985): zero velocity and
///    acceleration at both ends of every segment.
enum class Profile { kLinear, kMinimumJerk };

inline constexpr NamedValue<Profile> kProfileNames[] = {{Profile::kLinear, "linear"},
                                                        {Profile::kMinimumJerk, "minimum_jerk"}};
/// The profiles' names: "linear", "minimum_jerk".
constexpr std::span<const NamedValue<Profile>> name_table(Profile) {
  return kProfileNames;
}

/// The profile named `name` (InputError otherwise, with a suggestion).
Profile parse_profile(const std::string& name);

/// Normalised progress s ∈ [0, 1] and its derivative ds/dτ at τ (clamped to [0, 1]).
struct ProfileSample {
  double s = 0.0;
  double ds = 0.0;
};
ProfileSample sample_profile(Profile profile, double tau);

/// A piecewise trajectory: from `start` at `t0` through each waypoint in turn, each segment
/// taking its waypoint's duration. Before t0 it holds `start`, after the end the last waypoint
/// (with zero velocity). sample() allocates nothing.
class JointTrajectory {
 public:
  struct Waypoint {
    Eigen::VectorXd position;  ///< [rad]/[m], size num_joints()
    double duration_s = 1.0;   ///< time from the previous waypoint [s], > 0
  };

  JointTrajectory() = default;
  /// InputError if a waypoint has the wrong size ("expected N joint values, got M") or a
  /// non-positive duration.
  JointTrajectory(Profile profile, double t0, Eigen::VectorXd start,
                  std::vector<Waypoint> waypoints);

  int num_joints() const { return static_cast<int>(start_.size()); }
  int num_waypoints() const { return static_cast<int>(waypoints_.size()); }
  Profile profile() const { return profile_; }
  double start_time() const { return t0_; }
  double end_time() const { return end_times_.empty() ? t0_ : end_times_.back(); }
  /// True once the last waypoint is reached (t >= end_time()).
  bool finished(double t) const { return t >= end_time(); }
  /// Index of the waypoint being approached at t (num_waypoints() once finished).
  int segment_at(double t) const;
  const Eigen::VectorXd& final_position() const {
    return waypoints_.empty() ? start_ : waypoints_.back().position;
  }

  /// Reference position and velocity at time t [s].
  void sample(double t, Eigen::Ref<Eigen::VectorXd> position,
              Eigen::Ref<Eigen::VectorXd> velocity) const;

 private:
  Profile profile_ = Profile::kMinimumJerk;
  double t0_ = 0.0;
  Eigen::VectorXd start_;
  std::vector<Waypoint> waypoints_;
  std::vector<double> end_times_;  ///< absolute end time of each segment [s]
};

}  // namespace somasim::control
