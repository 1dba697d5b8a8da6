#include "robot_multibody.hpp"

#include <Eigen/Eigenvalues>

#include "body_tag.hpp"
#include "bullet_math.hpp"

namespace somasim::bullet_world {
namespace {

struct BodyFrame {
  Eigen::Isometry3d in_link = Eigen::Isometry3d::Identity();
  double mass = kFrameLinkMass;
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Constant(kMinPrincipalInertia);
};

// Centre of mass with principal axes (a proper rotation), the diagonal inertia and the mass.
BodyFrame body_frame(const robot::Inertial& inertial) {
  BodyFrame f;
  if (inertial.mass <= 0.0) return f;
  f.mass = inertial.mass;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertial.inertia);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  f.in_link.linear() = axes;
  f.in_link.translation() = inertial.com;
  f.principal_inertia = eig.eigenvalues().cwiseMax(kMinPrincipalInertia);
  return f;
}

robot::Geometry frame_link_placeholder() {
  robot::Geometry g;
  g.type = robot::GeometryType::Sphere;
  g.radius = 1e-3;
  return g;
}

}  // namespace

RobotMultiBody::RobotMultiBody(std::shared_ptr<const robot::RobotModel> model,
                               btMultiBodyDynamicsWorld& world, ShapeStore& shapes,
                               const Eigen::VectorXd& q, const LinkMaterial& material)
    : model_(std::move(model)), world_(world) {
  const robot::RobotModel& m = *model_;
  const int n = m.num_links();
  std::vector<BodyFrame> frames(n);
  for (int i = 0; i < n; ++i) frames[i] = body_frame(m.link(i).inertial);
  body_in_link_.resize(n);
  for (int i = 0; i < n; ++i) body_in_link_[i] = frames[i].in_link;

  multibody_ =
      std::make_unique<btMultiBody>(n - 1, frames[0].mass, to_bt(frames[0].principal_inertia),
                                    /*fixedBase=*/true, /*canSleep=*/false);
  const Eigen::Isometry3d& base = frames[0].in_link;
  multibody_->setBasePos(to_bt(Eigen::Vector3d(base.translation())));
  multibody_->setWorldToBaseRot(to_bt_quat(base.linear().transpose()));

  dof_link_.assign(m.num_dofs(), -1);
  for (int i = 1; i < n; ++i) {
    const robot::Link& link = m.link(i);
    const robot::Joint& j = m.joint(link.parent_joint);
    const Eigen::Isometry3d& cp = frames[link.parent_link].in_link;
    const Eigen::Isometry3d& cc = frames[i].in_link;
    // Child body frame in the frame after `pre · M(q)`, and its rotation.
    const Eigen::Matrix3d rot_post_body = j.post.linear() * cc.linear();
    const Eigen::Vector3d pivot_to_com =
        rot_post_body.transpose() * (j.post.translation() + j.post.linear() * cc.translation());
    const Eigen::Vector3d axis = rot_post_body.transpose() * j.axis;
    Eigen::Matrix3d pre_rot = j.pre.linear();
    Eigen::Vector3d pivot = j.pre.translation();
    if (j.type == robot::JointType::Revolute)
      pre_rot = pre_rot * Eigen::AngleAxisd(j.offset, j.axis).toRotationMatrix();
    else if (j.type == robot::JointType::Prismatic)
      pivot += j.pre.linear() * (j.offset * j.axis);
    // Orientation of the child body frame in the parent body frame at q = 0.
    const Eigen::Matrix3d child_in_parent = cp.linear().transpose() * pre_rot * rot_post_body;
    const btQuaternion parent_to_this = to_bt_quat(child_in_parent.transpose());
    const btVector3 com_to_pivot =
        to_bt(Eigen::Vector3d(cp.linear().transpose() * (pivot - cp.translation())));
    const btVector3 inertia = to_bt(frames[i].principal_inertia);
    const int parent = link.parent_link - 1;
    switch (j.type) {
      case robot::JointType::Revolute:
        multibody_->setupRevolute(i - 1, frames[i].mass, inertia, parent, parent_to_this,
                                  to_bt(axis), com_to_pivot, to_bt(pivot_to_com), false);
        break;
      case robot::JointType::Prismatic:
        multibody_->setupPrismatic(i - 1, frames[i].mass, inertia, parent, parent_to_this,
                                   to_bt(axis), com_to_pivot, to_bt(pivot_to_com), false);
        break;
      case robot::JointType::Fixed:
        multibody_->setupFixed(i - 1, frames[i].mass, inertia, parent, parent_to_this, com_to_pivot,
                               to_bt(pivot_to_com), false);
        break;
    }
    if (j.dof >= 0) dof_link_[j.dof] = i - 1;
  }
  multibody_->finalizeMultiDof();
  multibody_->setHasSelfCollision(true);  // pairs are filtered by SelfCollisionFilter
  multibody_->setLinearDamping(0.0);
  multibody_->setAngularDamping(0.0);
  multibody_->setUseGyroTerm(true);
  for (int d = 0; d < m.num_dofs(); ++d) {
    multibody_->setJointPos(dof_link_[d], q[d]);
    multibody_->setJointVel(dof_link_[d], 0.0);
  }
  world_.addMultiBody(multibody_.get());

  colliders_.resize(n);
  for (int i = 0; i < n; ++i) {
    auto col = std::make_unique<btMultiBodyLinkCollider>(multibody_.get(), i - 1);
    const bool has_geometry = !m.link(i).collision.empty();
    if (has_geometry) {
      col->setCollisionShape(shapes.make_compound(m.link(i).collision, frames[i].in_link.inverse(),
                                                  MeshUse::kConvexHull));
      set_tag(*col, {BodyKind::kLink, i, /*immovable=*/i == 0});
    } else {
      // Geometry-less frame links still need a collider that never collides: Bullet assigns a
      // multibody constraint (a motor) to a simulation island through the colliders of its two
      // links, and a constraint without an island is silently never solved.
      col->setCollisionShape(shapes.make(frame_link_placeholder(), MeshUse::kConvexHull));
      set_tag(*col, {BodyKind::kNone, i, false});
    }
    col->setFriction(material.friction);
    col->setRollingFriction(material.rolling_friction);
    col->setRestitution(material.restitution);
    if (has_geometry)
      world_.addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter,
                                btBroadphaseProxy::AllFilter);
    else
      world_.addCollisionObject(col.get(), /*group=*/0, /*mask=*/0);
    if (i == 0)
      multibody_->setBaseCollider(col.get());
    else
      multibody_->getLink(i - 1).m_collider = col.get();
    colliders_[i] = std::move(col);
  }
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  multibody_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
}

RobotMultiBody::~RobotMultiBody() {
  for (auto& col : colliders_)
    if (col) world_.removeCollisionObject(col.get());
  world_.removeMultiBody(multibody_.get());
}

void RobotMultiBody::read_joint_state(JointState& state) const {
  const int n = static_cast<int>(dof_link_.size());
  state.position.resize(n);
  state.velocity.resize(n);
  for (int d = 0; d < n; ++d) {
    state.position[d] = multibody_->getJointPos(dof_link_[d]);
    state.velocity[d] = multibody_->getJointVel(dof_link_[d]);
  }
}

void RobotMultiBody::link_poses(std::vector<Eigen::Isometry3d>& poses) const {
  // Same recursion as btMultiBody::updateCollisionObjectWorldTransforms.
  const int nl = multibody_->getNumLinks();
  world_to_local_.resize(nl + 1);
  local_origin_.resize(nl + 1);
  world_to_local_[0] = multibody_->getWorldToBaseRot();
  local_origin_[0] = multibody_->getBasePos();
  for (int k = 0; k < nl; ++k) {
    const int parent = multibody_->getParent(k);
    world_to_local_[k + 1] = multibody_->getParentToLocalRot(k) * world_to_local_[parent + 1];
    local_origin_[k + 1] = local_origin_[parent + 1] +
                           quatRotate(world_to_local_[k + 1].inverse(), multibody_->getRVector(k));
  }
  poses.resize(nl + 1);
  for (int i = 0; i <= nl; ++i) {
    const btTransform body(world_to_local_[i].inverse(), local_origin_[i]);
    poses[i] = to_eigen(body) * body_in_link_[i].inverse();
  }
}

}  // namespace somasim::bullet_world
