#include "robot_multibody.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "body_tag.hpp"
#include "bullet_math.hpp"
#include "somasim/error.hpp"

namespace somasim::bullet_world {
namespace {

struct BodyFrame {
  Eigen::Isometry3d in_rep = Eigen::Isometry3d::Identity();
  double mass = kFrameLinkMass;
  Eigen::Vector3d principal_inertia = Eigen::Vector3d::Constant(kMinPrincipalInertia);
};

// Mass, centre of mass and inertia (about it) of a group's links, in the representative's frame.
robot::Inertial group_inertial(const robot::RobotModel& model, const RigidGroups& groups, int rep) {
  robot::Inertial sum;
  for (int i = rep; i < model.num_links(); ++i) {
    const robot::Inertial& in = model.link(i).inertial;
    if (groups.rep[i] != rep || in.mass <= 0.0) continue;
    sum.com += in.mass * (groups.in_rep[i] * in.com);
    sum.mass += in.mass;
  }
  if (sum.mass <= 0.0) return sum;
  sum.com /= sum.mass;
  for (int i = rep; i < model.num_links(); ++i) {
    const robot::Inertial& in = model.link(i).inertial;
    if (groups.rep[i] != rep || in.mass <= 0.0) continue;
    const Eigen::Matrix3d r = groups.in_rep[i].linear();
    const Eigen::Vector3d d = groups.in_rep[i] * in.com - sum.com;
    sum.inertia += r * in.inertia * r.transpose() +
                   in.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return sum;
}

// Centre of mass with principal axes (a proper rotation), the diagonal inertia and the mass.
BodyFrame body_frame(const robot::Inertial& inertial) {
  BodyFrame f;
  if (inertial.mass <= 0.0) return f;
  f.mass = inertial.mass;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertial.inertia);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  f.in_rep.linear() = axes;
  f.in_rep.translation() = inertial.com;
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
                               const Eigen::VectorXd& q, const LinkMaterial& material,
                               const std::vector<bool>& locked, const std::vector<bool>& kinematic)
    : model_(std::move(model)),
      world_(world),
      groups_(*model_, locked, q),
      q_locked_(q),
      q_kinematic_(q),
      dq_kinematic_(Eigen::VectorXd::Zero(q.size())),
      fk_(*model_) {
  const robot::RobotModel& m = *model_;
  const auto dofs = static_cast<std::size_t>(m.num_dofs());
  locked_ = locked.empty() ? std::vector<bool>(dofs, false) : locked;
  kinematic_ = kinematic.empty() ? std::vector<bool>(dofs, false) : kinematic;
  SOMASIM_CHECK(locked_.size() == dofs && kinematic_.size() == dofs, "per-dof masks");
  any_kinematic_ = std::find(kinematic_.begin(), kinematic_.end(), true) != kinematic_.end();
  const std::vector<int>& reps = groups_.representatives;
  const int nb = static_cast<int>(reps.size());
  std::vector<BodyFrame> frames(nb);
  body_in_rep_.resize(nb);
  body_kinematic_.assign(static_cast<std::size_t>(nb), false);
  // The multibody's links: the bodies behind dynamic joints, in body order (parents first).
  std::vector<int> mb_link(static_cast<std::size_t>(nb), -1);
  mb_body_ = {0};
  for (int b = 0; b < nb; ++b) {
    frames[b] = body_frame(group_inertial(m, groups_, reps[b]));
    body_in_rep_[b] = frames[b].in_rep;
    if (b == 0) continue;
    const int dof = m.joint(m.link(reps[b]).parent_joint).dof;
    body_kinematic_[static_cast<std::size_t>(b)] = kinematic_[static_cast<std::size_t>(dof)];
    if (body_kinematic_[static_cast<std::size_t>(b)]) continue;
    mb_link[static_cast<std::size_t>(b)] = static_cast<int>(mb_body_.size()) - 1;
    mb_body_.push_back(b);
  }
  const int links = static_cast<int>(mb_body_.size()) - 1;

  dof_link_.assign(m.num_dofs(), -1);
  if (links > 0) {
    multibody_ =
        std::make_unique<btMultiBody>(links, frames[0].mass, to_bt(frames[0].principal_inertia),
                                      /*fixedBase=*/true, /*canSleep=*/false);
    const Eigen::Isometry3d& base = frames[0].in_rep;
    multibody_->setBasePos(to_bt(Eigen::Vector3d(base.translation())));
    multibody_->setWorldToBaseRot(to_bt_quat(base.linear().transpose()));
    for (int k = 0; k < links; ++k) {
      const int b = mb_body_[static_cast<std::size_t>(k) + 1];
      const robot::Link& link = m.link(reps[b]);
      const robot::Joint& j = m.joint(link.parent_joint);
      // The joint's parent link may be folded: express `pre` in the parent representative frame.
      const int parent_rep = groups_.rep[link.parent_link];
      const int parent_body = groups_.body_of_rep[parent_rep];
      const int parent_mb = mb_link[static_cast<std::size_t>(parent_body)];
      SOMASIM_CHECK(parent_body == 0 || parent_mb >= 0, "a dynamic joint below a kinematic one");
      const Eigen::Isometry3d pre = groups_.in_rep[link.parent_link] * j.pre;
      const Eigen::Isometry3d& cp = frames[parent_body].in_rep;
      const Eigen::Isometry3d& cc = frames[b].in_rep;
      // Child body frame in the frame after `pre · M(q)`, and its rotation.
      const Eigen::Matrix3d rot_post_body = j.post.linear() * cc.linear();
      const Eigen::Vector3d pivot_to_com =
          rot_post_body.transpose() * (j.post.translation() + j.post.linear() * cc.translation());
      const Eigen::Vector3d axis = rot_post_body.transpose() * j.axis;
      Eigen::Matrix3d pre_rot = pre.linear();
      Eigen::Vector3d pivot = pre.translation();
      if (j.type == robot::JointType::Revolute)
        pre_rot = pre_rot * Eigen::AngleAxisd(j.offset, j.axis).toRotationMatrix();
      else if (j.type == robot::JointType::Prismatic)
        pivot += pre.linear() * (j.offset * j.axis);
      // Orientation of the child body frame in the parent body frame at q = 0.
      const Eigen::Matrix3d child_in_parent = cp.linear().transpose() * pre_rot * rot_post_body;
      const btQuaternion parent_to_this = to_bt_quat(child_in_parent.transpose());
      const btVector3 com_to_pivot =
          to_bt(Eigen::Vector3d(cp.linear().transpose() * (pivot - cp.translation())));
      const btVector3 inertia = to_bt(frames[b].principal_inertia);
      if (j.type == robot::JointType::Revolute)
        multibody_->setupRevolute(k, frames[b].mass, inertia, parent_mb, parent_to_this,
                                  to_bt(axis), com_to_pivot, to_bt(pivot_to_com), false);
      else  // representatives are only reached through unlocked movable joints
        multibody_->setupPrismatic(k, frames[b].mass, inertia, parent_mb, parent_to_this,
                                   to_bt(axis), com_to_pivot, to_bt(pivot_to_com), false);
      dof_link_[j.dof] = k;
    }
    multibody_->finalizeMultiDof();
    multibody_->setHasSelfCollision(true);  // pairs are filtered by SelfCollisionFilter
    multibody_->setLinearDamping(0.0);
    multibody_->setAngularDamping(0.0);
    multibody_->setUseGyroTerm(true);
    for (int d = 0; d < m.num_dofs(); ++d) {
      if (dof_link_[d] < 0) continue;
      multibody_->setJointPos(dof_link_[d], q[d]);
      multibody_->setJointVel(dof_link_[d], 0.0);
    }
    world_.addMultiBody(multibody_.get());
  }

  child_link_.resize(m.num_links());
  colliders_.resize(nb);
  motion_states_.resize(nb);
  if (any_kinematic_) robot::forward_kinematics(m, fk_, q);
  for (int b = 0; b < nb; ++b) {
    const int r = reps[b];
    // The group's geometry in the representative's frame; child k belongs to child_link_[r][k].
    std::vector<robot::Geometry> geometry;
    for (int i = r; i < m.num_links(); ++i) {
      if (groups_.rep[i] != r) continue;
      for (robot::Geometry g : m.link(i).collision) {
        g.origin = groups_.in_rep[i] * g.origin;
        geometry.push_back(g);
        child_link_[r].push_back(i);
      }
    }
    const bool has_geometry = !geometry.empty();
    // A kinematic body posed by move_kinematic().
    const bool moved = body_kinematic_[static_cast<std::size_t>(b)];
    if (moved && !has_geometry) continue;  // nothing to collide, no motor to carry
    std::unique_ptr<btCollisionObject> col;
    if (multibody_ && !moved) {
      col = std::make_unique<btMultiBodyLinkCollider>(multibody_.get(),
                                                      mb_link[static_cast<std::size_t>(b)]);
    } else if (moved) {
      const Eigen::Isometry3d pose = fk_.link_poses[static_cast<std::size_t>(r)] * frames[b].in_rep;
      motion_states_[b] = std::make_unique<btDefaultMotionState>(to_bt(pose));
      btRigidBody::btRigidBodyConstructionInfo info(0.0, motion_states_[b].get(), nullptr);
      auto body = std::make_unique<btRigidBody>(info);
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
      col = std::move(body);
    } else {
      col = std::make_unique<btCollisionObject>();
    }
    if (has_geometry) {
      col->setCollisionShape(
          shapes.make_compound(geometry, frames[b].in_rep.inverse(), MeshUse::kConvexHull));
      set_tag(*col, {BodyKind::kLink, r, /*immovable=*/b == 0 || moved, /*kinematic=*/moved});
    } else {
      // Geometry-less bodies still need a collider that never collides: Bullet assigns a
      // multibody constraint (a motor) to a simulation island through the colliders of its two
      // links, and a constraint without an island is silently never solved.
      col->setCollisionShape(shapes.make(frame_link_placeholder(), MeshUse::kConvexHull));
      set_tag(*col, {BodyKind::kNone, r, false});
    }
    col->setFriction(material.friction);
    col->setRollingFriction(material.rolling_friction);
    col->setRestitution(material.restitution);
    if (!multibody_ && !moved) {
      // Static geometry at its (constant) pose: the whole robot when every dof is locked, the
      // root's group when every other joint is kinematic.
      col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      col->setWorldTransform(to_bt(frames[0].in_rep));
    }
    if (moved)
      world_.addRigidBody(static_cast<btRigidBody*>(col.get()), btBroadphaseProxy::DefaultFilter,
                          btBroadphaseProxy::AllFilter);  // the pair filter decides
    else if (has_geometry)
      world_.addCollisionObject(col.get(), btBroadphaseProxy::DefaultFilter,
                                btBroadphaseProxy::AllFilter);
    else
      world_.addCollisionObject(col.get(), /*group=*/0, /*mask=*/0);
    if (multibody_ && !moved) {
      auto* link_col = static_cast<btMultiBodyLinkCollider*>(col.get());
      if (b == 0)
        multibody_->setBaseCollider(link_col);
      else
        multibody_->getLink(mb_link[static_cast<std::size_t>(b)]).m_collider = link_col;
    }
    colliders_[b] = std::move(col);
  }
  if (multibody_) {
    btAlignedObjectArray<btQuaternion> world_to_local;
    btAlignedObjectArray<btVector3> local_origin;
    multibody_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
  }
  rep_pose_.assign(nb, Eigen::Isometry3d::Identity());
}

RobotMultiBody::~RobotMultiBody() {
  for (auto& col : colliders_)
    if (col) world_.removeCollisionObject(col.get());
  if (multibody_) world_.removeMultiBody(multibody_.get());
}

void RobotMultiBody::move_kinematic(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) {
  SOMASIM_CHECK(any_kinematic_, "move_kinematic() without kinematic joints");
  q_kinematic_ = q;
  dq_kinematic_ = dq;
  robot::forward_kinematics(*model_, fk_, q);
  const std::vector<int>& reps = groups_.representatives;
  for (std::size_t b = 1; b < reps.size(); ++b)
    if (body_kinematic_[b] && motion_states_[b])
      motion_states_[b]->setWorldTransform(
          to_bt(fk_.link_poses[static_cast<std::size_t>(reps[b])] * body_in_rep_[b]));
}

void RobotMultiBody::read_joint_state(JointState& state) const {
  const int n = static_cast<int>(dof_link_.size());
  state.position.resize(n);
  state.velocity.resize(n);
  for (int d = 0; d < n; ++d) {
    state.position[d] = position(d);
    state.velocity[d] = velocity(d);
  }
}

void RobotMultiBody::link_poses(std::vector<Eigen::Isometry3d>& poses) const {
  if (any_kinematic_ && !multibody_) {
    poses = fk_.link_poses;
    return;
  }
  if (multibody_) {
    // Same recursion as btMultiBody::updateCollisionObjectWorldTransforms.
    const int nl = multibody_->getNumLinks();
    world_to_local_.resize(nl + 1);
    local_origin_.resize(nl + 1);
    world_to_local_[0] = multibody_->getWorldToBaseRot();
    local_origin_[0] = multibody_->getBasePos();
    for (int k = 0; k < nl; ++k) {
      const int parent = multibody_->getParent(k);
      world_to_local_[k + 1] = multibody_->getParentToLocalRot(k) * world_to_local_[parent + 1];
      local_origin_[k + 1] =
          local_origin_[parent + 1] +
          quatRotate(world_to_local_[k + 1].inverse(), multibody_->getRVector(k));
    }
    for (int k = 0; k <= nl; ++k) {
      const btTransform body(world_to_local_[k].inverse(), local_origin_[k]);
      const int b = mb_body_[static_cast<std::size_t>(k)];
      rep_pose_[b] = to_eigen(body) * body_in_rep_[b].inverse();
    }
    // Kinematic groups under dynamic joints: where move_kinematic() put them.
    const std::vector<int>& reps = groups_.representatives;
    for (std::size_t b = 1; b < reps.size(); ++b)
      if (body_kinematic_[b]) rep_pose_[b] = fk_.link_poses[static_cast<std::size_t>(reps[b])];
  }  // else: static robot, the root group at the identity
  const int n = model_->num_links();
  poses.resize(n);
  for (int i = 0; i < n; ++i) {
    const int r = groups_.rep[i];
    const Eigen::Isometry3d& rep_pose = rep_pose_[groups_.body_of_rep[r]];
    poses[i] = r == i ? rep_pose : rep_pose * groups_.in_rep[i];
  }
}

}  // namespace somasim::bullet_world
