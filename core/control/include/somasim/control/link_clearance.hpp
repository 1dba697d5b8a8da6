#pragma once
/// @file
/// A quick distance check between two groups of robot links (e.g. the two arms during a
/// self-touch), on capsule bounds of their collision shapes: a capsule is itself, a cylinder the
/// capsule of the same radius and length (its rims rounded: slightly inside the cylinder there),
/// a sphere a zero-length capsule, a box a capsule along its longest edge whose radius is half
/// the diagonal of its cross-section (outside the box). Meshes are skipped.
///
/// Units: [m]; poses in the root frame.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::control {

/// A collision shape bounded by a capsule, in its link's frame.
struct LinkCapsule {
  int link = -1;
  int shape = -1;  ///< index in the link's collision list
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  ///< segment [m]
  double radius = 0.0;                                                       ///< [m]
};

/// Capsule bounds of every collision shape of `link` (meshes skipped).
std::vector<LinkCapsule> link_capsules(const robot::RobotModel& model, int link);

/// Shortest distance between segments [p0, p1] and [q0, q1] [m].
double segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

/// The closest pair found by LinkClearance::check.
struct ClearanceResult {
  double distance = 1e300;  ///< surface distance [m] (negative: overlapping bounds)
  int link_a = -1, link_b = -1;
  int shape_a = -1, shape_b = -1;  ///< indices in the links' collision lists
};

class LinkClearance {
 public:
  /// Distances between the shapes of `group_a` and `group_b` (link indices), except the shape
  /// pairs listed in `ignored` ({link, shape index} of a group-a shape — shape −1: all shapes of
  /// the link —, link of group b).
  struct Ignored {
    int link_a = -1, shape_a = -1, link_b = -1;
  };
  LinkClearance(const robot::RobotModel& model, const std::vector<int>& group_a,
                const std::vector<int>& group_b, std::vector<Ignored> ignored = {});

  /// The closest pair for link poses (root <- link, model order).
  ClearanceResult check(const std::vector<Eigen::Isometry3d>& link_poses) const;

 private:
  std::vector<LinkCapsule> a_, b_;
  std::vector<Ignored> ignored_;
};

}  // namespace somasim::control
