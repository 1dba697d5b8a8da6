#include "workspace_guard.hpp"

#include <algorithm>
#include <utility>

namespace somasim::plugins {

namespace {
constexpr int kBisections = 12;  // the factor to 1/4096 of the commanded velocity
constexpr double kSlack = 1e-9;  // [m]
}  // namespace

WorkspaceGuard::WorkspaceGuard(std::shared_ptr<const robot::RobotModel> model, int link,
                               std::vector<Eigen::Vector3d> points_link,
                               const Eigen::VectorXd& home_q, double radius)
    : model_(std::move(model)),
      link_(link),
      points_link_(std::move(points_link)),
      radius_(radius),
      data_(*model_) {
  robot::forward_kinematics(*model_, data_, home_q);
  const Eigen::Isometry3d& pose = data_.link_poses[static_cast<std::size_t>(link_)];
  for (const auto& p : points_link_) home_points_.push_back(pose * p);
}

void WorkspaceGuard::distances(const Eigen::VectorXd& q, std::vector<double>& out) {
  robot::forward_kinematics(*model_, data_, q);
  const Eigen::Isometry3d& pose = data_.link_poses[static_cast<std::size_t>(link_)];
  out.resize(points_link_.size());
  for (std::size_t i = 0; i < points_link_.size(); ++i)
    out[i] = (pose * points_link_[i] - home_points_[i]).norm();
}

double WorkspaceGuard::max_distance(const Eigen::VectorXd& q) {
  distances(q, d_);
  return d_.empty() ? 0.0 : *std::max_element(d_.begin(), d_.end());
}

double WorkspaceGuard::limit(const Eigen::VectorXd& q, const std::vector<int>& dofs,
                             JointCommand& cmd, double horizon_s) {
  distances(q, d0_);
  Eigen::VectorXd qa = q;
  const auto inside_at = [&](double scale) {
    for (int d : dofs) qa[d] = q[d] + scale * cmd.velocity[d] * horizon_s;
    distances(qa, d_);
    for (std::size_t i = 0; i < d_.size(); ++i)
      if (d_[i] > std::max(radius_, d0_[i]) + kSlack) return false;
    return true;
  };
  if (inside_at(1.0)) return 1.0;
  double lo = 0.0, hi = 1.0;  // lo keeps the points inside (no motion does)
  for (int k = 0; k < kBisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (inside_at(mid) ? lo : hi) = mid;
  }
  for (int d : dofs) cmd.velocity[d] *= lo;
  return lo;
}

}  // namespace somasim::plugins
