#pragma once
/// @file
/// The robot model in Bullet: a btMultiBody with a fixed base and one Bullet link per unlocked
/// dof. Links joined by fixed joints, and by joints locked at their initial value
/// (`locked_joints`), are folded into the body of their rigid group (rigid_groups.hpp): masses
/// and inertias are combined, collision shapes go into the group's btCompoundShape at their
/// fixed transforms. With every dof locked (or none in the model) there is no multibody at all:
/// the robot is one static collision object.
///
/// Frames: each Bullet body frame sits at its group's centre of mass with its principal axes of
/// inertia (Bullet needs a diagonal inertia); `body_in_rep` keeps that frame relative to the
/// group representative's link frame, so link poses are reported in the model's convention
/// (folded links: representative pose × constant transform). The world frame is the model's
/// root frame.
///
/// Collision objects carry a BodyTag{kLink, representative link}; contacts name the model link
/// through the compound child index (model_link()).
#include <memory>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <LinearMath/btDefaultMotionState.h>

#include <Eigen/Geometry>

#include "collision_shapes.hpp"
#include "rigid_groups.hpp"
#include "somasim/name_table.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::bullet_world {

/// Surface properties of the robot's links.
struct LinkMaterial {
  double friction = 0.8;
  double rolling_friction = 0.0;  ///< [m]
  double restitution = 0.0;
};

/// How the joints that are not locked move.
enum class JointMotion : std::uint8_t {
  kDynamic,    ///< a btMultiBody: motors, limits, contacts push back (the default)
  kKinematic,  ///< each rigid group a kinematic body posed by forward kinematics of the commands:
               ///< exact tracking, contacts reported (forces on dynamic objects from the solver)
};
inline constexpr NamedValue<JointMotion> kJointMotionNames[] = {
    {JointMotion::kDynamic, "dynamic"}, {JointMotion::kKinematic, "kinematic"}};
constexpr std::span<const NamedValue<JointMotion>> name_table(JointMotion) {
  return kJointMotionNames;
}

/// Mass and inertia given to massless bodies (Featherstone needs positive values).
inline constexpr double kFrameLinkMass = 0.02;        ///< [kg]
inline constexpr double kMinPrincipalInertia = 1e-5;  ///< [kg·m²]

class RobotMultiBody {
 public:
  /// Builds the robot at joint values `q` (model dof order) and adds it to `world`. `locked`:
  /// per dof, true = fixed at q (empty: none locked). `kinematic`: per dof, true = moved
  /// kinematically (empty: none); a kinematic joint's subtree holds only kinematic or locked
  /// joints (rigid_groups.hpp: kinematic_dofs()). The rigid groups behind kinematic joints are
  /// kinematic rigid bodies that move_kinematic() poses; the others form a multibody (none when
  /// every joint is locked or kinematic).
  RobotMultiBody(std::shared_ptr<const robot::RobotModel> model, btMultiBodyDynamicsWorld& world,
                 ShapeStore& shapes, const Eigen::VectorXd& q, const LinkMaterial& material,
                 const std::vector<bool>& locked = {}, const std::vector<bool>& kinematic = {});
  ~RobotMultiBody();
  RobotMultiBody(const RobotMultiBody&) = delete;
  RobotMultiBody& operator=(const RobotMultiBody&) = delete;

  const robot::RobotModel& model() const { return *model_; }
  const RigidGroups& groups() const { return groups_; }
  /// False when every dof is locked: no multibody, the robot is static geometry.
  bool has_multibody() const { return multibody_ != nullptr; }
  btMultiBody& multibody() { return *multibody_; }
  const btMultiBody& multibody() const { return *multibody_; }
  /// Bullet link index of a dof; -1 for locked and kinematic dofs.
  int dof_link(int dof) const { return dof_link_[dof]; }
  bool locked(int dof) const { return locked_[static_cast<std::size_t>(dof)]; }
  bool kinematic(int dof) const { return kinematic_[static_cast<std::size_t>(dof)]; }
  /// True when some joint moves kinematically (move_kinematic() poses its group each step).
  bool any_kinematic() const { return any_kinematic_; }

  /// Joint values/velocities (model dof order) [rad], [rad/s]; locked dofs: their fixed value, 0.
  double position(int dof) const {
    if (dof_link_[dof] >= 0) return multibody_->getJointPos(dof_link_[dof]);
    return locked(dof) ? q_locked_[dof] : q_kinematic_[dof];
  }
  double velocity(int dof) const {
    if (dof_link_[dof] >= 0) return multibody_->getJointVel(dof_link_[dof]);
    return locked(dof) ? 0.0 : dq_kinematic_[dof];
  }
  /// The kinematic joints move to `q` with velocities `dq` (model dof order) by the next physics
  /// step; their bodies' poses follow (Bullet derives their velocities). The other entries of
  /// `q` must hold the current joint values: a kinematic group under dynamic joints is posed
  /// from their values before the step (it lags their motion by one step).
  void move_kinematic(const Eigen::VectorXd& q, const Eigen::VectorXd& dq);
  void read_joint_state(JointState& state) const;

  /// Poses of all model links in the root frame (model link frames), in link order.
  void link_poses(std::vector<Eigen::Isometry3d>& poses) const;

  /// The model link of child `child_index` of the collision compound of the group represented by
  /// `rep_link` (a BodyTag index); `rep_link` itself when the index is out of range.
  int model_link(int rep_link, int child_index) const {
    const std::vector<int>& children = child_link_[rep_link];
    return child_index >= 0 && child_index < static_cast<int>(children.size())
               ? children[child_index]
               : rep_link;
  }

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  btMultiBodyDynamicsWorld& world_;
  RigidGroups groups_;
  std::vector<bool> locked_;     ///< per dof
  std::vector<bool> kinematic_;  ///< per dof
  bool any_kinematic_ = false;
  std::vector<bool> body_kinematic_;  ///< per body (groups_.representatives order)
  std::vector<int> mb_body_;          ///< per multibody link + 1 (0: the base): the body
  Eigen::VectorXd q_locked_;
  Eigen::VectorXd q_kinematic_, dq_kinematic_;                        ///< kinematic joints' state
  std::vector<std::unique_ptr<btDefaultMotionState>> motion_states_;  ///< per body (kinematic)
  mutable robot::RobotData fk_;                 ///< link poses at the last move_kinematic()
  std::vector<Eigen::Isometry3d> body_in_rep_;  ///< per body (groups_.representatives order)
  std::vector<int> dof_link_;
  std::vector<std::vector<int>> child_link_;  ///< per model link (representatives only)
  std::unique_ptr<btMultiBody> multibody_;
  std::vector<std::unique_ptr<btCollisionObject>> colliders_;  ///< per body
  mutable std::vector<btQuaternion> world_to_local_;
  mutable std::vector<btVector3> local_origin_;
  mutable std::vector<Eigen::Isometry3d> rep_pose_;  ///< per body
};

}  // namespace somasim::bullet_world
