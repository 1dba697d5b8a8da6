#pragma once
/// @file
/// Writing any somasim robot as a MuJoCo model (MJCF, `somasim robot export-mjcf`), so that the
/// same robot can be stepped by MuJoCo beside bullet_world: the same frames, joint axes and
/// limits, masses, centres of mass and inertias, collision shapes and self-collision exemptions.
///
/// Form, not meaning, changes: every link is a body nested under its parent (the root welded to
/// the world at `base_pose`); a movable joint's `pre · M(offset) · post` is the child body's pose
/// at q = 0 and the joint's axis and anchor are written in the child's frame, so MuJoCo's qpos
/// holds somasim's q and every body's pose equals the link's; fixed joints weld bodies. MuJoCo
/// numbers joints in the order of the tree as written (mjcf_joint_dofs), which is somasim's dof
/// order when dofs are numbered depth first (as in every shipped robot); actuators are written
/// in dof order (ctrl[d] drives dof d). Bodies, joints and actuators keep the model's names. Only
/// collision shapes are written (a capsule stays a capsule; meshes reference their files).
/// Pairs of links that somasim never tests against each other (collision_exempt_links) become
/// `<contact><exclude>` pairs.
///
/// What a physics engine needs and a kinematic description may lack is filled in as bullet_world
/// does: a moving group of links without mass gets `frame_link_mass` and principal inertias are
/// at least `min_principal_inertia`. Each movable joint gets a position servo: an MJCF `general`
/// actuator named after the joint (force = kp·ctrl − kp·q, clamped to ±max_torque) and the
/// joint's damping kd (MuJoCo integrates joint damping implicitly, so a light link cannot make the
/// servo unstable), kp = I·ω², kd = 2·I·ω critically damped at the bandwidth ω for I, the
/// joint-space inertia of the joint at `posture` (coupling neglected). ctrl = q* + (kd/kp)·q̇* +
/// τ_ff/kp gives kp·(q* − q) + kd·(q̇* − q̇) + τ_ff up to the torque bound.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

struct MjcfOptions {
  double timestep = 1e-3;                                       ///< [s]
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);       ///< world frame [m/s²]
  Eigen::Isometry3d base_pose = Eigen::Isometry3d::Identity();  ///< root link in the world
  double friction = 0.8;  ///< sliding friction of every geom [-]
  /// Torsional and rolling friction of every geom [m]; > 0 writes condim 6 (bullet_world's
  /// rolling_friction), 0 condim 3 (sliding friction only).
  double rolling_friction = 0.0;
  double frame_link_mass = 0.02;           ///< [kg], a moving group that has none
  double min_principal_inertia = 1e-5;     ///< [kg·m²]
  bool servos = true;                      ///< one position servo per movable joint
  double servo_bandwidth = 40.0;           ///< ω [1/s]
  double max_torque = 20.0;                ///< [N·m] (prismatic: [N])
  std::optional<Eigen::VectorXd> posture;  ///< where the servo inertias are taken (default q = 0)
};

/// The position gain kp [N·m/rad] and damping kd [N·m·s/rad] of each dof's servo (dof order),
/// as written by to_mjcf.
struct ServoGains {
  Eigen::VectorXd kp, kd;
};
ServoGains mjcf_servo_gains(const RobotModel& model, const MjcfOptions& options = {});

/// somasim's dof of each MJCF joint, in MuJoCo's order (its qpos/qvel index).
std::vector<int> mjcf_joint_dofs(const RobotModel& model);

/// The robot as an MJCF document (UTF-8 XML). Mesh files are written as absolute paths.
std::string to_mjcf(const RobotModel& model, const MjcfOptions& options = {});

}  // namespace somasim::robot
