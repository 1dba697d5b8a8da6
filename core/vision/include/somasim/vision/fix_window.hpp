#pragma once
/// @file
/// The last fixes of one track and the straight lines through them: the velocity its positions
/// show (a check of the velocity a filter reports) and how fast its radius changes (a rigid
/// object keeps its size: a radius that grows or shrinks is a track still settling onto its
/// object, or two eyes whose windows hold different parts of the scene).
///
/// Times [s], positions in any one fixed frame [m], velocities in that frame [m/s], radii [m].
#include <cstddef>
#include <deque>

#include <Eigen/Core>

namespace somasim::vision {

class FixWindow {
 public:
  /// Holds the last `capacity` fixes (at least 2); throws somasim::InputError otherwise.
  explicit FixWindow(int capacity = 5);

  /// Forget every fix (a new track).
  void clear() { fixes_.clear(); }
  /// A fix at `time_s` of an object of radius `radius_m` (0: unknown); fixes come in time order
  /// (an earlier one throws std::logic_error).
  void add(double time_s, const Eigen::Vector3d& position_m, double radius_m = 0.0);

  int size() const { return static_cast<int>(fixes_.size()); }
  int capacity() const { return capacity_; }
  bool full() const { return size() == capacity_; }

  /// The slope of the least-squares line through the fixes held, per axis [m/s]; zero with fewer
  /// than two fixes or all at one time.
  Eigen::Vector3d velocity() const;

  /// The slope of the least-squares line through the fixes' radii, in magnitude, over their mean
  /// radius [1/s]: the fraction of its size the object gains or loses per second. Zero with fewer
  /// than two fixes, all at one time, or a mean radius of 0.
  double radius_rate() const;

 private:
  struct Fix {
    double time_s;
    Eigen::Vector4d position_radius;  // x y z [m], radius [m]
  };
  // The least-squares slope of each of position_radius' components over time.
  Eigen::Vector4d slope() const;
  int capacity_;
  std::deque<Fix> fixes_;
};

}  // namespace somasim::vision
