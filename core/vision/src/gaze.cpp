#include "somasim/vision/gaze.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::vision {

GazeSolver::GazeSolver(std::shared_ptr<const robot::RobotModel> model, GazeOptions options)
    : model_(std::move(model)), options_(std::move(options)) {
  try {
    for (const std::string& j : options_.neck_joints) dofs_.push_back(model_->dof_index(j));
    for (const std::string& j : options_.eye_joints) dofs_.push_back(model_->dof_index(j));
  } catch (const InputError& e) {
    throw InputError(fmt::format("gaze: {}", e.what()));
  }
  neck_count_ = static_cast<int>(options_.neck_joints.size());
  if (options_.cameras.size() != 2)
    throw InputError(fmt::format("gaze: expected 2 cameras, got {}", options_.cameras.size()));
  robot::RobotData data(*model_);
  robot::forward_kinematics(*model_, data, Eigen::VectorXd::Zero(model_->num_dofs()));
  for (const std::string& c : options_.cameras) {
    try {
      render::camera_for(*model_, c, data.link_poses);
    } catch (const InputError& e) {
      throw InputError(fmt::format("gaze: {}", e.what()));
    }
  }
}

Eigen::VectorXd GazeSolver::residual(const Eigen::VectorXd& q, const Eigen::Vector3d& target,
                                     double centring, bool& behind) const {
  robot::RobotData data(*model_);
  robot::forward_kinematics(*model_, data, q);
  const auto eyes = static_cast<Eigen::Index>(options_.eye_joints.size());
  Eigen::VectorXd r(4 + eyes);
  behind = false;
  for (int c = 0; c < 2; ++c) {
    const render::Camera cam =
        render::camera_for(*model_, options_.cameras[static_cast<std::size_t>(c)], data.link_poses);
    const Eigen::Vector3d p = cam.to_camera(target);
    if (p.z() <= 1e-6) behind = true;
    // Angular offsets from the optical axis (atan2 stays smooth behind the camera too).
    r[2 * c] = std::atan2(p.x(), p.z());
    r[2 * c + 1] = std::atan2(p.y(), p.z());
  }
  for (Eigen::Index e = 0; e < eyes; ++e)
    r[4 + e] = centring * q[dofs_[static_cast<std::size_t>(neck_count_ + e)]];
  return r;
}

GazeSolution GazeSolver::solve(const Eigen::VectorXd& q0, const Eigen::Vector3d& target) const {
  const Eigen::VectorXd& lo = model_->lower_limits();
  const Eigen::VectorXd& hi = model_->upper_limits();
  Eigen::VectorXd q = q0;
  for (const int d : dofs_) q[d] = std::clamp(q[d], lo[d], hi[d]);
  const auto n = static_cast<Eigen::Index>(dofs_.size());
  bool behind = false;
  Eigen::VectorXd r;
  // First with the eyes pulled toward 0 (the neck points), then without it, so that the point
  // ends exactly on both axes (the pull only chose among the solutions).
  for (int it = 0; it < 2 * options_.iterations; ++it) {
    const double centring = it < options_.iterations ? options_.eye_centring : 0.0;
    r = residual(q, target, centring, behind);
    Eigen::MatrixXd jac(r.size(), n);
    for (Eigen::Index k = 0; k < n; ++k) {  // central differences
      const int d = dofs_[static_cast<std::size_t>(k)];
      const double h = 1e-6;
      Eigen::VectorXd qp = q, qm = q;
      qp[d] += h;
      qm[d] -= h;
      bool b = false;
      jac.col(k) =
          (residual(qp, target, centring, b) - residual(qm, target, centring, b)) / (2 * h);
    }
    const double damping = 1e-4;
    const Eigen::MatrixXd a = jac.transpose() * jac + damping * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd step = a.ldlt().solve(-jac.transpose() * r);
    for (Eigen::Index k = 0; k < n; ++k) {
      const int d = dofs_[static_cast<std::size_t>(k)];
      // At most 0.3 rad per iteration: the atan residual is far from linear for big turns.
      q[d] = std::clamp(q[d] + std::clamp(step[k], -0.3, 0.3), lo[d], hi[d]);
    }
    if (step.norm() < 1e-12 && it >= options_.iterations) break;
  }
  r = residual(q, target, 0.0, behind);
  GazeSolution s;
  s.q = q;
  s.behind = behind;
  s.residual_rad = r.head(4).cwiseAbs().maxCoeff();
  for (std::size_t k = 0; k < dofs_.size(); ++k) {
    const int d = dofs_[k];
    if (q[d] <= lo[d] + 1e-9 || q[d] >= hi[d] - 1e-9)
      s.at_limit.push_back(k < static_cast<std::size_t>(neck_count_)
                               ? options_.neck_joints[k]
                               : options_.eye_joints[k - static_cast<std::size_t>(neck_count_)]);
  }
  return s;
}

}  // namespace somasim::vision
