#include "somasim/robot/inverse_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "somasim/error.hpp"

namespace somasim::robot {

IkSolver::IkSolver(const KinematicChain& chain, IkOptions options)
    : chain_(chain),
      options_(options),
      jacobian_(6, chain.num_dofs()),
      q_try_(chain.num_dofs()),
      q_best_(chain.num_dofs()),
      dq_(chain.num_dofs()),
      frozen_(chain.num_dofs(), false) {}

IkResult IkSolver::solve_position(const Eigen::Vector3d& target, Eigen::Ref<Eigen::VectorXd> q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = target;
  return solve(t, false, q);
}

IkResult IkSolver::solve_pose(const Eigen::Isometry3d& target, Eigen::Ref<Eigen::VectorXd> q) {
  return solve(target, true, q);
}

// Weighted error vector (position [m]; orientation [rad] × weight) and its norm.
double IkSolver::error(const Eigen::Isometry3d& target, const Eigen::Isometry3d& tip,
                       bool with_orientation, Eigen::Matrix<double, 6, 1>& e) const {
  e.head<3>() = target.translation() - tip.translation();
  if (with_orientation) {
    const Eigen::AngleAxisd aa(target.linear() * tip.linear().transpose());
    e.tail<3>() = options_.orientation_weight * aa.angle() * aa.axis();
  } else {
    e.tail<3>().setZero();
  }
  return e.norm();
}

IkResult IkSolver::solve(const Eigen::Isometry3d& target, bool with_orientation,
                         Eigen::Ref<Eigen::VectorXd> q) {
  const int n = chain_.num_dofs();
  if (q.size() != n)
    throw InputError("inverse kinematics: expected " + std::to_string(n) + " joint values, got " +
                     std::to_string(q.size()));
  const Eigen::VectorXd& lo = chain_.lower_limits();
  const Eigen::VectorXd& hi = chain_.upper_limits();
  const int rows = with_orientation ? 6 : 3;
  std::mt19937_64 rng(options_.seed);
  IkResult result;
  double best = INFINITY;
  Eigen::Isometry3d tip;
  Eigen::Matrix<double, 6, 1> e, e_try;
  Eigen::Matrix<double, 6, 6> a;
  Eigen::Matrix<double, 6, 1> y;

  const auto converged = [&](const Eigen::Isometry3d& pose) {
    const double pe = (target.translation() - pose.translation()).norm();
    double oe = 0;
    if (with_orientation)
      oe = Eigen::AngleAxisd(target.linear() * pose.linear().transpose()).angle();
    return std::pair{pe, oe};
  };

  for (int attempt = 0; attempt <= options_.restarts; ++attempt) {
    if (attempt == 0) {
      q_try_ = q.cwiseMax(lo).cwiseMin(hi);
    } else {
      for (int k = 0; k < n; ++k)
        q_try_[k] = std::uniform_real_distribution<double>(lo[k], hi[k])(rng);
    }
    double lambda = options_.initial_damping;
    chain_.forward_jacobian(q_try_, tip, jacobian_);
    double err = error(target, tip, with_orientation, e);
    for (int it = 0; it < options_.max_iterations; ++it) {
      ++result.iterations;
      const auto [pe, oe] = converged(tip);
      if (err < best) {
        best = err;
        q_best_ = q_try_;
        result.position_error = pe;
        result.orientation_error = oe;
      }
      if (pe <= options_.position_tolerance && oe <= options_.orientation_tolerance) {
        result.success = true;
        q = q_best_;
        return result;
      }
      if (with_orientation) jacobian_.bottomRows<3>() *= options_.orientation_weight;
      // Active set: freeze joints at a limit whose step would push them out (two passes).
      std::fill(frozen_.begin(), frozen_.end(), false);
      for (int pass = 0; pass < 3; ++pass) {
        for (int k = 0; k < n; ++k)
          if (frozen_[k]) jacobian_.col(k).setZero();
        a.topLeftCorner(rows, rows).noalias() =
            jacobian_.topRows(rows) * jacobian_.topRows(rows).transpose();
        a.topLeftCorner(rows, rows).diagonal().array() += lambda * lambda;
        if (rows == 3)
          y.head<3>() = a.topLeftCorner<3, 3>().ldlt().solve(e.head<3>());
        else
          y = a.ldlt().solve(e);
        dq_.noalias() = jacobian_.topRows(rows).transpose() * y.head(rows);
        bool changed = false;
        for (int k = 0; k < n; ++k) {
          if (frozen_[k]) continue;
          if ((q_try_[k] <= lo[k] + 1e-12 && dq_[k] < 0) ||
              (q_try_[k] >= hi[k] - 1e-12 && dq_[k] > 0)) {
            frozen_[k] = true;
            changed = true;
          }
        }
        if (!changed) break;
      }
      const double largest = dq_.cwiseAbs().maxCoeff();
      if (largest > options_.max_step) dq_ *= options_.max_step / largest;
      // Levenberg–Marquardt: accept improving steps and relax damping, else damp harder.
      dq_ += q_try_;
      dq_ = dq_.cwiseMax(lo).cwiseMin(hi);
      const Eigen::Isometry3d before = tip;
      chain_.forward_jacobian(dq_, tip, jacobian_);
      const double err_try = error(target, tip, with_orientation, e_try);
      if (err_try < err) {
        q_try_.swap(dq_);
        err = err_try;
        e = e_try;
        lambda = std::max(lambda * 0.5, 1e-6);
      } else {
        lambda *= 4.0;
        tip = before;
        chain_.forward_jacobian(q_try_, tip, jacobian_);
        if (lambda > 1e3) break;  // stalled: restart
      }
    }
    const auto [pe, oe] = converged(tip);
    if (err < best) {
      best = err;
      q_best_ = q_try_;
      result.position_error = pe;
      result.orientation_error = oe;
    }
    if (pe <= options_.position_tolerance && oe <= options_.orientation_tolerance) {
      result.success = true;
      break;
    }
  }
  q = q_best_;
  return result;
}

}  // namespace somasim::robot
