#include "somasim/robot/kinematic_chain.hpp"

#include <cmath>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::robot {

namespace {

// A rotation whose z column is `axis` (so that a motion about/along axis = Q · M_z · Qᵀ).
Eigen::Matrix3d align_z(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x = helper.cross(z).normalized();
  Eigen::Matrix3d q;
  q.col(0) = x;
  q.col(1) = z.cross(x);
  q.col(2) = z;
  if ((z - Eigen::Vector3d::UnitZ()).norm() < 1e-15) q.setIdentity();
  return q;
}

}  // namespace

KinematicChain::KinematicChain(const RobotModel& model, const std::string& tip,
                               const std::string& base) {
  const FrameRef tip_ref = model.frame_ref(tip);
  const int base_link = base.empty() ? 0 : model.link_index(base);
  std::vector<int> path;  // joints from tip up to base
  int l = tip_ref.link;
  while (l != base_link) {
    if (l == 0)
      throw InputError("robot '" + model.name() + "': '" + tip + "' does not descend from link '" +
                       base + "'; expected a base link on the path from the root to the tip");
    path.push_back(model.link(l).parent_joint);
    l = model.link(l).parent_link;
  }
  Eigen::Isometry3d fixed = Eigen::Isometry3d::Identity();  // accumulated since the last joint
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const Joint& j = model.joint(*it);
    if (j.dof < 0) {
      fixed = fixed * j.pre * j.post;
      continue;
    }
    const Eigen::Matrix3d q = align_z(j.axis);
    Eigen::Isometry3d a = fixed * j.pre;
    a.linear() = a.linear() * q;
    steps_.push_back({a.linear(), a.translation(), j.offset, j.type == JointType::Prismatic});
    dofs_.push_back(j.dof);
    joint_names_.push_back(j.name);
    fixed = Eigen::Isometry3d::Identity();
    fixed.linear() = q.transpose();
    fixed = fixed * j.post;
  }
  fixed = fixed * tip_ref.pose;
  end_rotation_ = fixed.linear();
  end_translation_ = fixed.translation();
  lower_.resize(num_dofs());
  upper_.resize(num_dofs());
  for (int k = 0; k < num_dofs(); ++k) {
    lower_[k] = model.lower_limits()[dofs_[k]];
    upper_[k] = model.upper_limits()[dofs_[k]];
  }
}

KinematicChain KinematicChain::named(const RobotModel& model, const std::string& chain_name) {
  const ChainInfo* info = model.find_chain(chain_name);
  if (!info) {
    std::vector<std::string> names;
    for (const auto& c : model.chains()) names.push_back(c.name);
    throw InputError("robot '" + model.name() + "': unknown chain '" + chain_name + "'" +
                     did_you_mean(chain_name, names));
  }
  return KinematicChain(model, info->tip_frame, model.link(info->base_link).name);
}

void KinematicChain::gather(const Eigen::Ref<const Eigen::VectorXd>& model_q,
                            Eigen::Ref<Eigen::VectorXd> q) const {
  SOMASIM_CHECK(q.size() == num_dofs(), "chain q size");
  for (int k = 0; k < num_dofs(); ++k) q[k] = model_q[dofs_[k]];
}

void KinematicChain::check_sizes(Eigen::Index q, Eigen::Index offsets) const {
  if (q != num_dofs() || offsets != num_dofs())
    throw InputError("kinematic chain: expected " + std::to_string(num_dofs()) +
                     " joint values and offsets, got " + std::to_string(q) + " and " +
                     std::to_string(offsets));
}

template <class Angle>
void KinematicChain::evaluate(const Angle& angle, Eigen::Isometry3d& tip,
                              Eigen::Ref<Matrix6Xd>* jacobian) const {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  const int n = num_dofs();
  for (int k = 0; k < n; ++k) {
    const Step& s = steps_[k];
    t.noalias() += r * s.translation;
    r = r * s.rotation;  // Eigen evaluates into a temporary for aliasing (fixed size: no heap)
    const double v = angle(k) + s.offset;
    if (jacobian) {  // columns hold (origin, axis) until the tip is known
      (*jacobian).col(k).head<3>() = t;
      (*jacobian).col(k).tail<3>() = r.col(2);
    }
    if (s.prismatic) {
      t.noalias() += v * r.col(2);
    } else {
      double sn, cs;
      ::sincos(v, &sn, &cs);
      const Eigen::Vector3d c0 = r.col(0);
      r.col(0) = cs * c0 + sn * r.col(1);
      r.col(1) = cs * r.col(1) - sn * c0;
    }
  }
  t.noalias() += r * end_translation_;
  tip.linear() = r * end_rotation_;
  tip.translation() = t;
  tip.makeAffine();
  if (jacobian) {
    for (int k = 0; k < n; ++k) {
      auto col = (*jacobian).col(k);
      if (steps_[k].prismatic) {
        col.head<3>() = col.tail<3>();
        col.tail<3>().setZero();
      } else {
        const Eigen::Vector3d axis = col.tail<3>();
        col.head<3>() = axis.cross(t - col.head<3>());
      }
    }
  }
}

Eigen::Isometry3d KinematicChain::forward(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  check_sizes(q.size(), q.size());
  Eigen::Isometry3d tip;
  evaluate([&](int k) { return q[k]; }, tip, nullptr);
  return tip;
}

Eigen::Isometry3d KinematicChain::forward(const Eigen::Ref<const Eigen::VectorXd>& q,
                                          const Eigen::Ref<const Eigen::VectorXd>& offsets) const {
  check_sizes(q.size(), offsets.size());
  Eigen::Isometry3d tip;
  evaluate([&](int k) { return q[k] + offsets[k]; }, tip, nullptr);
  return tip;
}

void KinematicChain::forward_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      Eigen::Isometry3d& tip,
                                      Eigen::Ref<Matrix6Xd> jacobian) const {
  check_sizes(q.size(), jacobian.cols());
  evaluate([&](int k) { return q[k]; }, tip, &jacobian);
}

void KinematicChain::forward_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::VectorXd>& offsets,
                                      Eigen::Isometry3d& tip,
                                      Eigen::Ref<Matrix6Xd> jacobian) const {
  check_sizes(q.size(), offsets.size());
  check_sizes(q.size(), jacobian.cols());
  evaluate([&](int k) { return q[k] + offsets[k]; }, tip, &jacobian);
}

}  // namespace somasim::robot
