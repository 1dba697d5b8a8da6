#include "somasim/robot/dynamics.hpp"

namespace somasim::robot {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

/// Motion cross product V ×m M, both (ω, v).
Vector6d cross_motion(const Vector6d& v, const Vector6d& m) {
  Vector6d out;
  out << v.head<3>().cross(m.head<3>()),
      v.head<3>().cross(m.tail<3>()) + v.tail<3>().cross(m.head<3>());
  return out;
}

/// Force cross product V ×f F, V = (ω, v), F = (n, f).
Vector6d cross_force(const Vector6d& v, const Vector6d& f) {
  Vector6d out;
  out << v.head<3>().cross(f.head<3>()) + v.tail<3>().cross(f.tail<3>()),
      v.head<3>().cross(f.tail<3>());
  return out;
}

/// The joint's motion subspace at the root origin: revolute (u, r × u), prismatic (0, u).
Vector6d motion_subspace(const Joint& joint, const Eigen::Vector3d& axis,
                         const Eigen::Vector3d& origin) {
  Vector6d s;
  if (joint.type == JointType::Prismatic)
    s << Eigen::Vector3d::Zero(), axis;
  else
    s << axis, origin.cross(axis);
  return s;
}

}  // namespace

std::vector<Inertial> physical_inertials(const RobotModel& model, double frame_link_mass,
                                         double frame_link_inertia,
                                         const std::vector<bool>& locked) {
  const int n = model.num_links();
  std::vector<Inertial> out(n);
  std::vector<double> group_mass(n, 0.0);  // mass welded to each moving link (or the root)
  std::vector<int> mover(n, 0);
  auto welded = [&](const Link& link) {
    if (link.parent_joint < 0) return false;
    const int dof = model.joint(link.parent_joint).dof;
    return dof < 0 || (!locked.empty() && locked[static_cast<std::size_t>(dof)]);
  };
  for (int i = 0; i < n; ++i) {
    const Link& link = model.link(i);
    mover[i] = welded(link) ? mover[link.parent_link] : i;
    group_mass[mover[i]] += link.inertial.mass;
  }
  for (int i = 0; i < n; ++i) {
    out[i] = model.link(i).inertial;
    const bool moves = model.link(i).parent_joint >= 0 && mover[i] == i;
    if (moves && group_mass[i] <= 0.0) {
      out[i].mass = frame_link_mass;
      out[i].com.setZero();
      out[i].inertia = Eigen::Matrix3d::Identity() * frame_link_inertia;
    }
  }
  return out;
}

InverseDynamics::InverseDynamics(const RobotModel& model, std::vector<Inertial> inertials)
    : model_(model),
      inertials_(std::move(inertials)),
      velocity_(model.num_links()),
      acceleration_(model.num_links()),
      force_(model.num_links()),
      tau_(Eigen::VectorXd::Zero(model.num_dofs())) {}

const Eigen::VectorXd& InverseDynamics::torques(const RobotData& data,
                                                const Eigen::Ref<const Eigen::VectorXd>& qd,
                                                const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                                const Eigen::Vector3d& gravity) {
  const int n = model_.num_links();
  // The root is fixed; gravity enters as an upward acceleration of the root.
  velocity_[0].setZero();
  acceleration_[0] << Eigen::Vector3d::Zero(), -gravity;
  for (int i = 0; i < n; ++i) {
    const Link& link = model_.link(i);
    if (i > 0) {
      const int p = link.parent_link;
      const Joint& joint = model_.joint(link.parent_joint);
      velocity_[i] = velocity_[p];
      acceleration_[i] = acceleration_[p];
      if (joint.dof >= 0) {
        const Vector6d s = motion_subspace(joint, data.joint_axes[link.parent_joint],
                                           data.joint_origins[link.parent_joint]);
        velocity_[i] += s * qd[joint.dof];
        acceleration_[i] += s * qdd[joint.dof] + cross_motion(velocity_[i], s * qd[joint.dof]);
      }
    }
    const Inertial& in = inertials_[static_cast<std::size_t>(i)];
    if (in.mass <= 0.0) {
      force_[i].setZero();
      continue;
    }
    // Spatial inertia at the root origin from the mass, the centre c and the inertia about it.
    const Eigen::Matrix3d r = data.link_poses[i].linear();
    const Eigen::Vector3d c = data.link_poses[i] * in.com;
    const Eigen::Matrix3d cx = skew(c);
    const Eigen::Matrix3d rotational = r * in.inertia * r.transpose() - in.mass * cx * cx;
    auto inertia_times = [&](const Vector6d& m) {
      Vector6d f;
      f << rotational * m.head<3>() + in.mass * cx * m.tail<3>(),
          in.mass * (m.tail<3>() - cx * m.head<3>());
      return f;
    };
    force_[i] =
        inertia_times(acceleration_[i]) + cross_force(velocity_[i], inertia_times(velocity_[i]));
  }
  for (int i = n - 1; i > 0; --i) {
    const Link& link = model_.link(i);
    const Joint& joint = model_.joint(link.parent_joint);
    if (joint.dof >= 0)
      tau_[joint.dof] = motion_subspace(joint, data.joint_axes[link.parent_joint],
                                        data.joint_origins[link.parent_joint])
                            .dot(force_[i]);
    force_[link.parent_link] += force_[i];
  }
  return tau_;
}

}  // namespace somasim::robot
