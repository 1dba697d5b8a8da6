#include "somasim/robot/kinematics.hpp"

#include <string>

#include "somasim/error.hpp"

namespace somasim::robot {

RobotData::RobotData(const RobotModel& model)
    : q(Eigen::VectorXd::Zero(model.num_dofs())),
      offsets(Eigen::VectorXd::Zero(model.num_dofs())),
      link_poses(model.num_links(), Eigen::Isometry3d::Identity()),
      joint_axes(model.num_joints(), Eigen::Vector3d::UnitZ()),
      joint_origins(model.num_joints(), Eigen::Vector3d::Zero()) {}

namespace {

void check_size(const RobotModel& model, Eigen::Index n, const char* what) {
  if (n != model.num_dofs())
    throw InputError("robot '" + model.name() + "': expected " + std::to_string(model.num_dofs()) +
                     " " + what + ", got " + std::to_string(n));
}

void run_forward(const RobotModel& model, RobotData& data) {
  const auto& joints = model.joints();
  data.link_poses[0].setIdentity();
  for (int l = 1; l < model.num_links(); ++l) {
    const int ji = model.links()[l].parent_joint;
    const Joint& j = joints[ji];
    Eigen::Isometry3d t = data.link_poses[j.parent_link] * j.pre;
    data.joint_axes[ji].noalias() = t.linear() * j.axis;
    data.joint_origins[ji] = t.translation();
    if (j.dof >= 0) {
      const double v = data.q[j.dof] + data.offsets[j.dof] + j.offset;
      if (j.type == JointType::Revolute)
        t.linear() = t.linear() * Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
      else
        t.translation() += v * data.joint_axes[ji];
    }
    data.link_poses[l] = t * j.post;
  }
}

}  // namespace

void forward_kinematics(const RobotModel& model, RobotData& data,
                        const Eigen::Ref<const Eigen::VectorXd>& q) {
  check_size(model, q.size(), "joint values");
  SOMASIM_CHECK(data.link_poses.size() == static_cast<std::size_t>(model.num_links()),
                "RobotData was made for another model");
  data.q = q;
  run_forward(model, data);
}

void forward_kinematics(const RobotModel& model, RobotData& data,
                        const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& offsets) {
  check_size(model, offsets.size(), "joint offsets");
  data.offsets = offsets;
  forward_kinematics(model, data, q);
}

void point_jacobian(const RobotModel& model, const RobotData& data, int link,
                    const Eigen::Vector3d& point_in_link, Eigen::Ref<Matrix6Xd> jacobian) {
  SOMASIM_CHECK(link >= 0 && link < model.num_links(), "link index out of range");
  if (jacobian.cols() != model.num_dofs())
    throw InputError("robot '" + model.name() + "': expected a 6 x " +
                     std::to_string(model.num_dofs()) + " Jacobian, got 6 x " +
                     std::to_string(jacobian.cols()));
  jacobian.setZero();
  const Eigen::Vector3d p = data.link_poses[link] * point_in_link;
  for (int d : model.supporting_dofs(link)) {
    const int ji = model.dof_joint(d);
    const Eigen::Vector3d& axis = data.joint_axes[ji];
    if (model.joint(ji).type == JointType::Revolute) {
      jacobian.col(d).head<3>() = axis.cross(p - data.joint_origins[ji]);
      jacobian.col(d).tail<3>() = axis;
    } else {
      jacobian.col(d).head<3>() = axis;
    }
  }
}

}  // namespace somasim::robot
