#pragma once
/// @file
/// Cartesian velocity control of any point fixed to a link of a chain (issue 3):
///   q̇ = J⁺ v,   J⁺ = Jᵀ (J Jᵀ + λ² I)⁻¹   (damped least squares),
/// with J the point's position Jacobian (3 × chain dofs, root frame) — or, when holding the
/// link's orientation, the full 6-row Jacobian with ω = k_R · log(R_ref Rᵀ) as angular task.
///
/// Damping is adaptive (Maciejewski & Klein): λ² = λ_max² (1 − (σ_min/ε)²) when the smallest
/// singular value σ_min of J drops below ε, else 0, so the commanded speed is exact away from
/// singularities and bounded near them.
///
/// Joint limits: a joint whose velocity would carry it past [lower + margin, upper − margin]
/// within the next control period is clamped to reach the bound exactly and removed from the
/// solve; the remaining joints are solved again for the residual task (so the point keeps its
/// direction while other joints can provide it). A joint already past a bound may move back
/// but not further. Velocity limits: the whole solution is scaled down uniformly so that no
/// joint exceeds its limit (the direction of motion is kept, the speed drops).
///
/// Reused by cartesian_velocity (plugin) and pps_controller (which moves the voted point P).
/// compute() allocates nothing.
#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "somasim/control/chain_selection.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::control {

struct CartesianVelocityOptions {
  double damping = 0.02;             ///< λ_max [m]
  double singular_threshold = 0.04;  ///< ε [m]: damping ramps in below this singular value
  /// Per chain dof [rad/s] ([m/s] prismatic); size 1 = the same for all; empty = unlimited.
  Eigen::VectorXd max_joint_velocity;
  double limit_margin = 0.0;  ///< kept from each joint limit [rad]/[m]
  bool hold_orientation = false;
  double orientation_gain = 2.0;  ///< k_R [1/s]
};

class CartesianVelocityController {
 public:
  /// InputError for a bad max_joint_velocity size ("expected 1 or N values, got M").
  CartesianVelocityController(std::shared_ptr<const robot::RobotModel> model, ChainSelection chain,
                              CartesianVelocityOptions options = {});

  /// The controlled point: `point_in_link` [m, link frame] fixed to `link`, which must be in
  /// the chain (InputError as ChainSelection::require_link says). Resets the held orientation.
  void set_point(const std::string& link, const Eigen::Vector3d& point_in_link);
  void set_point(int link, const Eigen::Vector3d& point_in_link);
  int link() const { return link_; }
  const Eigen::Vector3d& point_in_link() const { return point_; }
  /// The next compute() captures the current link orientation as the one to hold.
  void reset_orientation() { have_orientation_ref_ = false; }

  /// Joint velocities of the chain dofs (chain order) [rad/s] that move the point at `velocity`
  /// [m/s, root frame], for the full model joint vector `q` and control period `dt` [s].
  /// RunError when q has the wrong size or holds NaN.
  void compute(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Vector3d& velocity,
               double dt, Eigen::Ref<Eigen::VectorXd> chain_qdot);
  /// Same, written as a whole-robot command: velocity mode on the chain dofs (position = q),
  /// kNone elsewhere. `command` is resized on first use.
  void compute(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Vector3d& velocity,
               double dt, JointCommand& command);

  /// After compute(): the point [m, root frame] at q, the point velocity J q̇ the returned
  /// velocities produce [m/s, root frame], and whether a limit changed the solution.
  const Eigen::Vector3d& point_position() const { return position_; }
  const Eigen::Vector3d& predicted_velocity() const { return predicted_; }
  bool limited() const { return limited_; }

  const ChainSelection& chain() const { return chain_; }
  const robot::RobotModel& model() const { return *model_; }
  const CartesianVelocityOptions& options() const { return options_; }

 private:
  void solve(int rows);  // DLS of task_ (rows) with columns of free joints

  std::shared_ptr<const robot::RobotModel> model_;
  ChainSelection chain_;
  CartesianVelocityOptions options_;
  robot::RobotData data_;
  int link_ = -1;
  Eigen::Vector3d point_ = Eigen::Vector3d::Zero();
  bool have_orientation_ref_ = false;
  Eigen::Matrix3d orientation_ref_ = Eigen::Matrix3d::Identity();
  // Work space (sized once).
  robot::Matrix6Xd full_jacobian_;
  robot::Matrix6Xd jacobian_;       ///< chain columns
  robot::Matrix6Xd jacobian_free_;  ///< chain columns, fixed joints zeroed
  Eigen::Matrix<double, 6, 1> task_, residual_;
  Eigen::VectorXd qdot_, command_qdot_, lower_rate_, upper_rate_, max_velocity_;
  std::vector<bool> fixed_;
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero(), predicted_ = Eigen::Vector3d::Zero();
  bool limited_ = false;
};

}  // namespace somasim::control
