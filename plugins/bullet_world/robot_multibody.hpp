#pragma once
/// @file
/// The robot model as a Bullet btMultiBody with a fixed base: one Bullet link per model link
/// (model link i ↔ Bullet link i − 1; the root is the base), joint types, axes, offsets and
/// origins taken from the model, collision shapes from each link's collision geometry, masses and
/// inertias from the model.
///
/// Frames: each Bullet link frame sits at the link's centre of mass with its principal axes of
/// inertia (Bullet needs a diagonal inertia); `body_in_link` keeps that frame relative to the
/// model's link frame, so link poses are reported in the model's convention. The world frame is
/// the model's root frame.
#include <memory>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <Eigen/Geometry>

#include "collision_shapes.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/robot_ports.hpp"

namespace somasim::bullet_world {

/// Surface properties of the robot's links.
struct LinkMaterial {
  double friction = 0.8;
  double rolling_friction = 0.0;  ///< [m]
  double restitution = 0.0;
};

/// Mass and inertia given to massless frame links (Featherstone needs positive values).
inline constexpr double kFrameLinkMass = 0.02;        ///< [kg]
inline constexpr double kMinPrincipalInertia = 1e-5;  ///< [kg·m²]

class RobotMultiBody {
 public:
  /// Builds the multibody at joint values `q` (model dof order) and adds it to `world`.
  RobotMultiBody(std::shared_ptr<const robot::RobotModel> model, btMultiBodyDynamicsWorld& world,
                 ShapeStore& shapes, const Eigen::VectorXd& q, const LinkMaterial& material);
  ~RobotMultiBody();
  RobotMultiBody(const RobotMultiBody&) = delete;
  RobotMultiBody& operator=(const RobotMultiBody&) = delete;

  const robot::RobotModel& model() const { return *model_; }
  btMultiBody& multibody() { return *multibody_; }
  const btMultiBody& multibody() const { return *multibody_; }
  /// Bullet link index of a dof.
  int dof_link(int dof) const { return dof_link_[dof]; }

  /// Joint values/velocities (model dof order) [rad], [rad/s].
  double position(int dof) const { return multibody_->getJointPos(dof_link_[dof]); }
  double velocity(int dof) const { return multibody_->getJointVel(dof_link_[dof]); }
  void read_joint_state(JointState& state) const;

  /// Poses of all model links in the root frame (model link frames), in link order.
  void link_poses(std::vector<Eigen::Isometry3d>& poses) const;

  /// Centre-of-mass frame of a model link, relative to the link frame.
  const Eigen::Isometry3d& body_in_link(int link) const { return body_in_link_[link]; }

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  btMultiBodyDynamicsWorld& world_;
  std::vector<Eigen::Isometry3d> body_in_link_;
  std::vector<int> dof_link_;
  std::unique_ptr<btMultiBody> multibody_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;  ///< per model link
  mutable std::vector<btQuaternion> world_to_local_;
  mutable std::vector<btVector3> local_origin_;
};

}  // namespace somasim::bullet_world
