#pragma once
/// @file
/// Rigid-body dynamics of the robot model: the mass properties a physics engine gives each link,
/// and inverse dynamics (recursive Newton–Euler), the torques that produce given joint
/// accelerations at given joint velocities under gravity.
///
/// Frames: the root frame (RobotData's), which is the world frame of a fixed-base robot placed at
/// the origin. Units: [m], [rad], [kg], [N·m] (prismatic joints: [N]).
#include <vector>

#include <Eigen/Core>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// The mass properties a physics engine needs (bullet_world's bodies, the MJCF export): each
/// link's own, except that a moving group of links without mass — a link moved by a joint that
/// is neither fixed nor in `locked` (per dof, empty: none), with the links welded to it — gets
/// `frame_link_mass` [kg] at its link's origin with inertia `frame_link_inertia` [kg·m²] about
/// each axis (the DH chains' frame links between two joints of one shoulder, say).
std::vector<Inertial> physical_inertials(const RobotModel& model, double frame_link_mass,
                                         double frame_link_inertia,
                                         const std::vector<bool>& locked = {});

/// Recursive Newton–Euler over the model's tree, in spatial vectors at the root origin:
/// τ = M(q)·q̈ + C(q, q̇)·q̇ + G(q), one pass out and one back, O(links). Reusable: sized once.
class InverseDynamics {
 public:
  /// `inertials`: one per link (e.g. physical_inertials), in the link frames.
  InverseDynamics(const RobotModel& model, std::vector<Inertial> inertials);

  /// Joint torques (dof order) at the posture of `data` (forward_kinematics done) with joint
  /// velocities `qd` [rad/s], accelerations `qdd` [rad/s²] and `gravity` [m/s², root frame].
  const Eigen::VectorXd& torques(const RobotData& data, const Eigen::Ref<const Eigen::VectorXd>& qd,
                                 const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                 const Eigen::Vector3d& gravity);

 private:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  const RobotModel& model_;
  std::vector<Inertial> inertials_;
  std::vector<Vector6d> velocity_, acceleration_, force_;  // per link
  Eigen::VectorXd tau_;
};

}  // namespace somasim::robot
