#include "somasim/body_schema/eye_hand.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "somasim/error.hpp"

namespace somasim::body_schema {

Vector6d pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  Vector6d e;
  e.head<3>() = a.translation() - b.translation();
  const Eigen::AngleAxisd r(a.linear() * b.linear().transpose());
  e.tail<3>() = r.angle() * r.axis();
  return e;
}

namespace {

const robot::Camera& find_camera(const robot::RobotModel& model, const std::string& name) {
  const int c = model.find_camera(name);
  if (c < 0) throw InputError(fmt::format("camera '{}' is not in robot '{}'", name, model.name()));
  return model.cameras()[static_cast<std::size_t>(c)];
}

}  // namespace

EyeHand::EyeHand(std::shared_ptr<const robot::RobotModel> model, const std::string& camera,
                 const std::string& palm, const std::string& arm_base)
    : model_(std::move(model)),
      camera_link_(find_camera(*model_, camera).link),
      camera_pose_(find_camera(*model_, camera).pose),
      palm_(model_->frame_ref(palm)),
      base_link_(model_->link_index(arm_base)),
      chain_(*model_, palm, arm_base),
      ik_(chain_),
      data_(*model_),
      jacobian_(6, model_->num_dofs()) {}

Eigen::Isometry3d EyeHand::eye_root(const Eigen::VectorXd& q) {
  robot::forward_kinematics(*model_, data_, q);
  return data_.link_poses[static_cast<std::size_t>(camera_link_)] * camera_pose_;
}

Eigen::Isometry3d EyeHand::palm_eye(const Eigen::VectorXd& q, const Eigen::VectorXd& offsets) {
  const Eigen::Isometry3d eye = eye_root(q);  // the head has no offsets
  robot::forward_kinematics(*model_, data_, q, offsets);
  return eye.inverse() * robot::frame_pose(data_, palm_);
}

Eigen::Isometry3d EyeHand::palm_eye(const std::vector<Eigen::Isometry3d>& link_poses) const {
  const Eigen::Isometry3d eye =
      link_poses.at(static_cast<std::size_t>(camera_link_)) * camera_pose_;
  return eye.inverse() * link_poses.at(static_cast<std::size_t>(palm_.link)) * palm_.pose;
}

robot::IkResult EyeHand::solve(const Eigen::Isometry3d& target_eye, Eigen::VectorXd& q) {
  const Eigen::Isometry3d eye = eye_root(q);
  const Eigen::Isometry3d base = data_.link_poses[static_cast<std::size_t>(base_link_)];
  const Eigen::Isometry3d target_base = base.inverse() * eye * target_eye;
  Eigen::VectorXd arm(chain_.num_dofs());
  chain_.gather(q, arm);
  const robot::IkResult result = ik_.solve_pose(target_base, arm);
  for (int k = 0; k < chain_.num_dofs(); ++k)
    q[chain_.dof_indices()[static_cast<std::size_t>(k)]] = arm[k];
  return result;
}

Eigen::VectorXd EyeHand::servo_step(const Eigen::VectorXd& q, const Eigen::VectorXd& offsets,
                                    const Eigen::Isometry3d& target_eye, double gain, double dt) {
  const Eigen::Isometry3d eye = eye_root(q);
  robot::forward_kinematics(*model_, data_, q, offsets);
  const Eigen::Isometry3d palm = eye.inverse() * robot::frame_pose(data_, palm_);
  robot::frame_jacobian(*model_, data_, palm_, jacobian_);
  const std::vector<int>& dofs = chain_.dof_indices();
  Eigen::MatrixXd j(6, static_cast<Eigen::Index>(dofs.size()));
  const Eigen::Matrix3d to_eye = eye.linear().transpose();
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    j.block<3, 1>(0, col) = to_eye * jacobian_.block<3, 1>(0, dofs[k]);
    j.block<3, 1>(3, col) = to_eye * jacobian_.block<3, 1>(3, dofs[k]);
  }
  const Vector6d e = pose_error(palm, target_eye);
  const Eigen::VectorXd dq = -gain * dt * j.completeOrthogonalDecomposition().pseudoInverse() * e;
  Eigen::VectorXd next = q;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    next[dofs[k]] =
        std::clamp(q[dofs[k]] + dq[col], chain_.lower_limits()[col], chain_.upper_limits()[col]);
  }
  return next;
}

}  // namespace somasim::body_schema
