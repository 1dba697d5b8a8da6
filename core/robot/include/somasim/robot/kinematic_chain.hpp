#pragma once
/// @file
/// A serial chain compiled from the tree (base link → tip frame) for fast FK and Jacobians:
/// fixed transforms are folded so that one step per movable joint remains,
///   T = A_0 · M_0(θ_0) · A_1 · M_1(θ_1) · ... · M_{n-1}(θ_{n-1}) · A_n,
/// with M_k a rotation about (or translation along) z and θ_k = q_k + offset_k (+ β_k).
/// Evaluation allocates nothing.
///
/// Frames: results are in the chain's base-link frame (the root frame for chains starting at the
/// root). Units: [m], [rad]. Jacobian: 6 × num_dofs, rows 0-2 linear, rows 3-5 angular.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

class KinematicChain {
 public:
  /// Chain from `base` (a link; "" = the root) to `tip` (a frame or link). InputError when a
  /// name is unknown or the tip does not descend from the base.
  KinematicChain(const RobotModel& model, const std::string& tip, const std::string& base = "");
  /// A named chain of the description (e.g. "right_arm"): base link → its tip frame.
  static KinematicChain named(const RobotModel& model, const std::string& chain_name);

  int num_dofs() const { return static_cast<int>(steps_.size()); }
  /// Model dof index of each chain joint (chain joint k ↔ model q[dof_indices()[k]]).
  const std::vector<int>& dof_indices() const { return dofs_; }
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  const Eigen::VectorXd& lower_limits() const { return lower_; }  ///< [rad]/[m]
  const Eigen::VectorXd& upper_limits() const { return upper_; }
  /// Chain joint values out of a full model joint vector.
  void gather(const Eigen::Ref<const Eigen::VectorXd>& model_q,
              Eigen::Ref<Eigen::VectorXd> q) const;

  /// Tip pose in the base frame for chain joint values q (size num_dofs).
  Eigen::Isometry3d forward(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// Same with per-joint offsets β added to q (the body-schema hypotheses).
  Eigen::Isometry3d forward(const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& offsets) const;
  /// Tip pose and geometric Jacobian of the tip origin (6 × num_dofs, base frame).
  void forward_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Isometry3d& tip,
                        Eigen::Ref<Matrix6Xd> jacobian) const;
  void forward_jacobian(const Eigen::Ref<const Eigen::VectorXd>& q,
                        const Eigen::Ref<const Eigen::VectorXd>& offsets, Eigen::Isometry3d& tip,
                        Eigen::Ref<Matrix6Xd> jacobian) const;

 private:
  struct Step {
    Eigen::Matrix3d rotation;     ///< of A_k
    Eigen::Vector3d translation;  ///< of A_k
    double offset = 0.0;
    bool prismatic = false;
  };
  // Angle(k) gives θ_k; jacobian may be null.
  template <class Angle>
  void evaluate(const Angle& angle, Eigen::Isometry3d& tip, Eigen::Ref<Matrix6Xd>* jacobian) const;
  void check_sizes(Eigen::Index q, Eigen::Index offsets) const;

  std::vector<Step> steps_;
  Eigen::Matrix3d end_rotation_ = Eigen::Matrix3d::Identity();  ///< A_n
  Eigen::Vector3d end_translation_ = Eigen::Vector3d::Zero();
  std::vector<int> dofs_;
  std::vector<std::string> joint_names_;
  Eigen::VectorXd lower_, upper_;
};

}  // namespace somasim::robot
