#include "somasim/control/touch_ik.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "somasim/error.hpp"

namespace somasim::control {

namespace {

// Dofs that move `link` (from the model's supporting dofs).
std::vector<int> moving(const robot::RobotModel& model, int link) {
  return model.supporting_dofs(link);
}

bool contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

TouchIk::TouchIk(std::shared_ptr<const robot::RobotModel> model, robot::FrameRef effector,
                 const Eigen::Vector3d& effector_axis, const Eigen::Vector3d& effector_side,
                 int target_link, const std::vector<int>& held_dofs, TouchIkOptions options)
    : model_(std::move(model)),
      effector_(std::move(effector)),
      target_link_(target_link),
      options_(options),
      data_(*model_) {
  const int links = model_->num_links();
  if (effector_.link < 0 || effector_.link >= links)
    throw InputError("touch IK: effector link index " + std::to_string(effector_.link) +
                     " is not a link of robot '" + model_->name() + "'");
  if (target_link_ < 0 || target_link_ >= links)
    throw InputError("touch IK: target link index " + std::to_string(target_link_) +
                     " is not a link of robot '" + model_->name() + "'");
  if (effector_axis.norm() < 1e-12) throw InputError("touch IK: the effector axis is zero");
  effector_axis_ = effector_axis.normalized();
  effector_side_ =
      effector_side.norm() < 1e-12 ? Eigen::Vector3d::Zero() : effector_side.normalized();

  const std::vector<int> e = moving(*model_, effector_.link);
  const std::vector<int> t = moving(*model_, target_link_);
  for (int d : e)
    if (!contains(t, d) && !contains(held_dofs, d)) dofs_.push_back(d);
  effector_dofs_ = static_cast<int>(dofs_.size());
  for (int d : t)
    if (!contains(e, d) && !contains(held_dofs, d)) dofs_.push_back(d);
  if (dofs_.empty())
    throw InputError("touch IK: no joint moves link '" + model_->link(effector_.link).name +
                     "' or link '" + model_->link(target_link_).name +
                     "' without moving both (nothing to solve)");
  const int n = static_cast<int>(dofs_.size());
  lower_.resize(n);
  upper_.resize(n);
  for (int k = 0; k < n; ++k) {
    const double lo = model_->lower_limits()[dofs_[k]], hi = model_->upper_limits()[dofs_[k]];
    const double margin = std::min(options_.limit_margin, 0.25 * (hi - lo));
    lower_[k] = lo + margin;
    upper_[k] = hi - margin;
  }
  j_effector_.setZero(6, model_->num_dofs());
  j_target_.setZero(6, model_->num_dofs());
  jacobian_.setZero(9, n);
}

double TouchIk::residual(const TouchTarget& target, const Eigen::VectorXd& q, bool jacobian) {
  robot::forward_kinematics(*model_, data_, q);
  const Eigen::Isometry3d& te = data_.link_poses[static_cast<std::size_t>(effector_.link)];
  const Eigen::Isometry3d& tt = data_.link_poses[static_cast<std::size_t>(target_link_)];
  const Eigen::Vector3d n = target.normal.normalized();
  Eigen::Vector3d t = target.tangent - target.tangent.dot(n) * n;
  const bool side = t.norm() > 1e-9 && effector_side_.norm() > 0;
  const double tilt = side ? target.tilt : 0.0;
  if (side) t.normalize();
  const Eigen::Vector3d point = target.point + target.distance * n;
  tip_ = te * effector_.pose.translation();
  axis_ = te.linear() * effector_axis_;
  side_ = te.linear() * effector_side_;
  goal_ = tt * point;
  axis_goal_ = tt.linear() * (-std::cos(tilt) * n + std::sin(tilt) * t);
  side_goal_ = side ? Eigen::Vector3d(tt.linear() * (std::sin(tilt) * n + std::cos(tilt) * t))
                    : Eigen::Vector3d::Zero();
  rows_ = side ? 9 : 6;
  const double w = target.axis_weight > 0 ? target.axis_weight : options_.axis_weight;
  r_.head<3>() = goal_ - tip_;
  r_.segment<3>(3) = w * (axis_goal_ - axis_);
  r_.tail<3>() = side ? Eigen::Vector3d(w * (side_goal_ - side_)) : Eigen::Vector3d::Zero();
  if (jacobian) {
    robot::point_jacobian(*model_, data_, effector_.link, effector_.pose.translation(),
                          j_effector_);
    robot::point_jacobian(*model_, data_, target_link_, point, j_target_);
    // d(R v)/dt = ω × (R v): goals turn with the target link, axes with the effector link.
    for (int k = 0; k < static_cast<int>(dofs_.size()); ++k) {
      const int d = dofs_[k];
      const Eigen::Vector3d we = j_effector_.block<3, 1>(3, d), wt = j_target_.block<3, 1>(3, d);
      jacobian_.block<3, 1>(0, k) = j_target_.block<3, 1>(0, d) - j_effector_.block<3, 1>(0, d);
      jacobian_.block<3, 1>(3, k) = w * (wt.cross(axis_goal_) - we.cross(axis_));
      jacobian_.block<3, 1>(6, k) =
          side ? Eigen::Vector3d(w * (wt.cross(side_goal_) - we.cross(side_)))
               : Eigen::Vector3d::Zero();
    }
  }
  return r_.head(rows_).norm();
}

TouchIkResult TouchIk::errors() const {
  const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  };
  TouchIkResult r;
  r.position_error = (goal_ - tip_).norm();
  r.axis_error = angle(axis_, axis_goal_);
  r.roll_error = rows_ == 9 ? angle(side_, side_goal_) : 0.0;
  return r;
}

bool TouchIk::converged(const TouchIkResult& r, const TouchTarget& target) const {
  const double axis_tol =
      target.axis_tolerance > 0 ? target.axis_tolerance : options_.axis_tolerance;
  return r.position_error <= options_.position_tolerance && r.axis_error <= axis_tol &&
         r.roll_error <= axis_tol;
}

TouchIkResult TouchIk::evaluate(const TouchTarget& target, const Eigen::VectorXd& q) {
  if (q.size() != model_->num_dofs())
    throw InputError("touch IK: expected " + std::to_string(model_->num_dofs()) +
                     " joint values, got " + std::to_string(q.size()));
  residual(target, q, false);
  TouchIkResult r = errors();
  r.success = converged(r, target);
  return r;
}

TouchIkResult TouchIk::solve(const TouchTarget& target, const Eigen::VectorXd& home,
                             Eigen::VectorXd& q) {
  const int nq = model_->num_dofs();
  if (q.size() != nq || home.size() != nq)
    throw InputError("touch IK: expected " + std::to_string(nq) + " joint values, got " +
                     std::to_string(q.size() != nq ? q.size() : home.size()));
  const int n = static_cast<int>(dofs_.size());
  std::mt19937_64 rng(options_.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto clamp_solved = [&](Eigen::VectorXd& v) {
    for (int k = 0; k < n; ++k) v[dofs_[k]] = std::clamp(v[dofs_[k]], lower_[k], upper_[k]);
  };

  TouchIkResult result;
  double best = INFINITY;
  const Eigen::VectorXd q_in = q;
  Eigen::VectorXd q_best = q, q_try(nq), q_new(nq), dq(n), z(n), scale(n);
  const double target_scale = 1.0 / std::sqrt(std::max(1.0, target.target_dof_cost));
  std::vector<bool> frozen(static_cast<std::size_t>(n));
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9>;
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 9, 1>;
  // Keeps q_try (with its errors `now`) when its residual `err` is the lowest so far.
  const auto keep_if_best = [&](double err, const TouchIkResult& now) {
    if (err >= best) return;
    best = err;
    q_best = q_try;
    result.position_error = now.position_error;
    result.axis_error = now.axis_error;
    result.roll_error = now.roll_error;
  };

  for (int attempt = 0; attempt <= options_.restarts; ++attempt) {
    q_try = q_in;  // the dofs not solved keep their values
    if (attempt >= 1)
      for (int k = 0; k < n; ++k) q_try[dofs_[k]] = home[dofs_[k]];
    if (attempt >= 2)
      for (int k = 0; k < n; ++k) q_try[dofs_[k]] += options_.restart_spread * gauss(rng);
    clamp_solved(q_try);
    double lambda = options_.initial_damping;
    double err = residual(target, q_try, true);
    for (int it = 0; it < options_.max_iterations; ++it) {
      ++result.iterations;
      TouchIkResult now = errors();
      keep_if_best(err, now);
      if (converged(now, target)) {
        result.success = true;
        q = q_try;
        result.position_error = now.position_error;
        result.axis_error = now.axis_error;
        result.roll_error = now.roll_error;
        return result;
      }
      // Weighted least norm: in scaled joints y = S⁻¹ q the target branch's dofs cost
      // `target_dof_cost` times more to move; the posture pull z acts in the null space.
      for (int k = 0; k < n; ++k) {
        scale[k] = k < effector_dofs_ ? 1.0 : target_scale;
        z[k] = options_.posture_gain * (home[dofs_[k]] - q_try[dofs_[k]]) / scale[k];
      }
      // Active set: freeze joints at a limit whose step would push them out.
      std::fill(frozen.begin(), frozen.end(), false);
      Eigen::Matrix<double, 9, Eigen::Dynamic> jf = jacobian_ * scale.asDiagonal();
      for (int pass = 0; pass < 3; ++pass) {
        for (int k = 0; k < n; ++k)
          if (frozen[static_cast<std::size_t>(k)]) {
            jf.col(k).setZero();
            z[k] = 0.0;
          }
        const auto j = jf.topRows(rows_);
        Small a = j * j.transpose();
        a.diagonal().array() += lambda * lambda;
        const auto ldlt = a.ldlt();
        const SmallVec y = ldlt.solve(r_.head(rows_));
        const SmallVec jz = j * z;
        const SmallVec yz = ldlt.solve(jz);
        dq = (-(j.transpose() * y) + z - j.transpose() * yz).cwiseProduct(scale);
        bool changed = false;
        for (int k = 0; k < n; ++k) {
          const auto kk = static_cast<std::size_t>(k);
          if (frozen[kk]) {
            dq[k] = 0.0;
            continue;
          }
          const double v = q_try[dofs_[k]];
          if ((v <= lower_[k] + 1e-12 && dq[k] < 0) || (v >= upper_[k] - 1e-12 && dq[k] > 0)) {
            frozen[kk] = true;
            changed = true;
          }
        }
        if (!changed) break;
      }
      const double largest = dq.cwiseAbs().maxCoeff();
      if (largest > options_.max_step) dq *= options_.max_step / largest;
      q_new = q_try;
      for (int k = 0; k < n; ++k) q_new[dofs_[k]] += dq[k];
      clamp_solved(q_new);
      const double err_new = residual(target, q_new, true);
      if (err_new < err) {
        q_try.swap(q_new);
        err = err_new;
        lambda = std::max(lambda * 0.5, 1e-5);
      } else {
        lambda *= 4.0;
        residual(target, q_try, true);
        if (lambda > 1e2) break;  // stalled: next attempt
      }
    }
    keep_if_best(err, errors());
  }
  q = q_best;
  return result;
}

}  // namespace somasim::control
