#pragma once
/// @file
/// The last fixes of one track and the velocity of the straight line through them: a check of
/// the velocity a filter reports against what the track's own positions show.
///
/// Times [s], positions in any one fixed frame [m], velocities in that frame [m/s].
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
  /// A fix at `time_s`; fixes come in time order (an earlier one throws std::logic_error).
  void add(double time_s, const Eigen::Vector3d& position_m);

  int size() const { return static_cast<int>(fixes_.size()); }
  int capacity() const { return capacity_; }
  bool full() const { return size() == capacity_; }

  /// The slope of the least-squares line through the fixes held, per axis [m/s]; zero with fewer
  /// than two fixes or all at one time.
  Eigen::Vector3d velocity() const;

 private:
  struct Fix {
    double time_s;
    Eigen::Vector3d position_m;
  };
  int capacity_;
  std::deque<Fix> fixes_;
};

}  // namespace somasim::vision
