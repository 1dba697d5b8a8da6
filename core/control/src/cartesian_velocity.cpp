#include "somasim/control/cartesian_velocity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "somasim/error.hpp"

namespace somasim::control {

CartesianVelocityController::CartesianVelocityController(
    std::shared_ptr<const robot::RobotModel> model, ChainSelection chain,
    CartesianVelocityOptions options)
    : model_(std::move(model)),
      chain_(std::move(chain)),
      options_(std::move(options)),
      data_(*model_) {
  const int n = static_cast<int>(chain_.dofs.size());
  const auto& mv = options_.max_joint_velocity;
  if (mv.size() != 0 && mv.size() != 1 && mv.size() != n)
    throw InputError("max joint velocity: expected 1 or " + std::to_string(n) +
                     " values (one per joint of chain '" + chain_.name + "'), got " +
                     std::to_string(mv.size()));
  max_velocity_ = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  if (mv.size() == 1) max_velocity_.setConstant(mv[0]);
  if (mv.size() == n && n > 0) max_velocity_ = mv;
  full_jacobian_.setZero(6, model_->num_dofs());
  jacobian_.setZero(6, n);
  jacobian_free_.setZero(6, n);
  qdot_.setZero(n);
  command_qdot_.setZero(n);
  lower_rate_.setZero(n);
  upper_rate_.setZero(n);
  fixed_.assign(n, false);
  link_ = chain_.tip_link;  // the tip link's origin until set_point()
}

void CartesianVelocityController::set_point(const std::string& link,
                                            const Eigen::Vector3d& point_in_link) {
  set_point(chain_.require_link(*model_, link), point_in_link);
}

void CartesianVelocityController::set_point(int link, const Eigen::Vector3d& point_in_link) {
  if (!chain_.contains_link(link))
    chain_.require_link(*model_, model_->link(link).name);  // throws the standard message
  link_ = link;
  point_ = point_in_link;
  have_orientation_ref_ = false;
}

void CartesianVelocityController::solve(int rows) {
  // qdot_free = Jfᵀ (Jf Jfᵀ + λ² I)⁻¹ r with fixed-size (≤ 6 × 6) temporaries.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  const auto jf = jacobian_free_.topRows(rows);
  Small m = jf * jf.transpose();
  const Eigen::SelfAdjointEigenSolver<Small> eig(m, Eigen::EigenvaluesOnly);
  const double sigma_min = std::sqrt(std::max(0.0, eig.eigenvalues().minCoeff()));
  const double eps = options_.singular_threshold;
  double lambda2 = 0.0;
  if (sigma_min < eps) {
    const double r = eps > 0.0 ? sigma_min / eps : 1.0;
    lambda2 = options_.damping * options_.damping * (1.0 - r * r);
  }
  m.diagonal().array() += lambda2;
  const SmallVec y = m.ldlt().solve(residual_.head(rows));
  for (int k = 0; k < qdot_.size(); ++k)
    if (!fixed_[k]) qdot_[k] = jf.col(k).dot(y);
}

void CartesianVelocityController::compute(const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Vector3d& velocity, double dt,
                                          Eigen::Ref<Eigen::VectorXd> chain_qdot) {
  const int n = static_cast<int>(chain_.dofs.size());
  if (q.size() != model_->num_dofs())
    throw RunError("cartesian velocity: expected " + std::to_string(model_->num_dofs()) +
                   " joint values, got " + std::to_string(q.size()));
  if (!q.allFinite() || !velocity.allFinite())
    throw RunError("cartesian velocity: non-finite joint values or commanded velocity");
  SOMASIM_CHECK(chain_qdot.size() == n, "chain_qdot size");
  SOMASIM_CHECK(link_ >= 0, "no controlled point");

  robot::forward_kinematics(*model_, data_, q);
  const Eigen::Isometry3d& pose = data_.link_poses[link_];
  position_ = pose * point_;
  robot::point_jacobian(*model_, data_, link_, point_, full_jacobian_);
  for (int k = 0; k < n; ++k) jacobian_.col(k) = full_jacobian_.col(chain_.dofs[k]);

  int rows = 3;
  task_.head<3>() = velocity;
  if (options_.hold_orientation) {
    if (!have_orientation_ref_) {
      orientation_ref_ = pose.linear();
      have_orientation_ref_ = true;
    }
    const Eigen::AngleAxisd err(orientation_ref_ * pose.linear().transpose());
    task_.tail<3>() = options_.orientation_gain * err.angle() * err.axis();
    rows = 6;
  }

  // Per-joint rate bounds from the position limits over the next period; 0 always allowed.
  for (int k = 0; k < n; ++k) {
    const int d = chain_.dofs[k];
    const double lo = model_->lower_limits()[d] + options_.limit_margin;
    const double hi = model_->upper_limits()[d] - options_.limit_margin;
    lower_rate_[k] = std::min(0.0, (lo - q[d]) / dt);
    upper_rate_[k] = std::max(0.0, (hi - q[d]) / dt);
  }

  std::fill(fixed_.begin(), fixed_.end(), false);
  jacobian_free_ = jacobian_;
  residual_ = task_;
  qdot_.setZero();
  limited_ = false;
  for (int iteration = 0; iteration <= n; ++iteration) {
    solve(rows);
    // The free joint that overshoots its bound the most (smallest admissible fraction).
    int worst = -1;
    double worst_fraction = 1.0;
    for (int k = 0; k < n; ++k) {
      if (fixed_[k]) continue;
      double fraction = 1.0;
      if (qdot_[k] > upper_rate_[k]) fraction = upper_rate_[k] / qdot_[k];
      if (qdot_[k] < lower_rate_[k]) fraction = lower_rate_[k] / qdot_[k];
      if (fraction < worst_fraction) {
        worst_fraction = fraction;
        worst = k;
      }
    }
    if (worst < 0) break;
    limited_ = true;
    qdot_[worst] = std::clamp(qdot_[worst], lower_rate_[worst], upper_rate_[worst]);
    fixed_[worst] = true;
    jacobian_free_.col(worst).setZero();
    residual_.head(rows).noalias() -= jacobian_.col(worst).head(rows) * qdot_[worst];
  }

  double scale = 1.0;
  for (int k = 0; k < n; ++k)
    if (std::abs(qdot_[k]) > max_velocity_[k])
      scale = std::min(scale, max_velocity_[k] / std::abs(qdot_[k]));
  if (scale < 1.0) {
    qdot_ *= scale;
    limited_ = true;
  }
  predicted_.noalias() = jacobian_.topRows<3>() * qdot_;
  chain_qdot = qdot_;
}

void CartesianVelocityController::compute(const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Vector3d& velocity, double dt,
                                          JointCommand& command) {
  const int nd = model_->num_dofs();
  if (static_cast<int>(command.mode.size()) != nd) {
    command.mode.assign(nd, JointCommandMode::kNone);
    command.position.setZero(nd);
    command.velocity.setZero(nd);
  }
  compute(q, velocity, dt, command_qdot_);
  for (int k = 0; k < static_cast<int>(chain_.dofs.size()); ++k) {
    const int d = chain_.dofs[k];
    command.mode[d] = JointCommandMode::kVelocity;
    command.position[d] = q[d];
    command.velocity[d] = command_qdot_[k];
  }
}

}  // namespace somasim::control
