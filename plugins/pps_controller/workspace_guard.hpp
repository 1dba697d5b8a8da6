#pragma once
// Keeps every point of a body part within a sphere of fixed radius around where that point was
// at the home posture: joint-velocity commands are scaled down (never redirected) so that, over
// the look-ahead horizon, no point leaves its sphere and a point already outside moves no
// further out. The controlled point is a weighted mean of the body part's taxels, so holding
// every taxel inside holds every point the controller can control (the spheres are convex and
// the link is rigid).
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class WorkspaceGuard {
 public:
  /// `points_link`: the body part's points in the frame of `link` [m]; `home_q`: the home
  /// posture [rad]; `radius` [m].
  WorkspaceGuard(std::shared_ptr<const robot::RobotModel> model, int link,
                 std::vector<Eigen::Vector3d> points_link, const Eigen::VectorXd& home_q,
                 double radius);

  /// The largest distance of any point from its home position at posture `q` [m].
  double max_distance(const Eigen::VectorXd& q);

  /// Scales the velocity targets of `dofs` in `cmd` (velocity mode) by the largest factor in
  /// [0, 1] that keeps the points inside over `horizon_s` when integrated from `q`. Returns it.
  double limit(const Eigen::VectorXd& q, const std::vector<int>& dofs, JointCommand& cmd,
               double horizon_s);

 private:
  // Distance of each point from its home position at q.
  void distances(const Eigen::VectorXd& q, std::vector<double>& out);

  std::shared_ptr<const robot::RobotModel> model_;
  int link_;
  std::vector<Eigen::Vector3d> points_link_, home_points_;
  double radius_;
  robot::RobotData data_;
  std::vector<double> d0_, d_;
};

}  // namespace somasim::plugins
