#pragma once
/// @file
/// Inverse kinematics of a self-touch (the iCub's double touch, Roncone et al. 2016): an effector
/// frame on one branch of the robot (the right index fingertip) meets a point on a link of another
/// branch (a taxel of the left forearm) at a given distance along the point's outward normal, with
/// the effector's pointing axis along the inward normal. Both branches are solved together; the
/// dofs they share (the torso) are held.
///
/// The effector's wanted orientation: axis a* = −cos θ n + sin θ t and, when a tangent t is
/// given, side s* = sin θ n + cos θ t (θ the tilt): with a hand whose other fingers lie along s,
/// a tilt lifts them off the skin while the touching finger meets it. Residuals (root frame),
/// stacked into one damped-least-squares problem on the solved dofs:
///   position  r_p = (T_target · (x + d·n)) − p_effector          (3)  [m]
///   axis      r_a = w_axis · (R_target a* − R_effector a)         (3, rank 2)
///   side      r_s = w_axis · (R_target s* − R_effector s)         (3, optional)
/// with x, n, t the target point, outward normal and tangent (target link frame), a and s the
/// effector's axis and side (effector link frame).
/// Steps: Levenberg–Marquardt damping, joint limits by clamping with an active set, and a
/// null-space pull toward a home posture (posture regularisation) so that solutions stay
/// comfortable and continuous along an approach.
///
/// Units: [m], [rad]. Joint vectors are full model vectors (RobotModel dof order).
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::control {

struct TouchIkOptions {
  int max_iterations = 300;          ///< per attempt
  int restarts = 4;                  ///< extra attempts: from home, then from perturbed homes
  double restart_spread = 0.3;       ///< σ of the perturbations of home for restarts [rad]
  double position_tolerance = 5e-4;  ///< [m]
  double axis_tolerance = 0.03;      ///< angle between the effector axis and −n [rad]
  double axis_weight = 0.1;          ///< w_axis [m per unit of axis error]
  double initial_damping = 1e-2;     ///< λ of (J Jᵀ + λ² I) [m]
  double max_step = 0.15;            ///< largest joint change per iteration [rad]
  double posture_gain = 0.1;         ///< fraction of (home − q) pulled per iteration (null space)
  double limit_margin = 0.02;        ///< kept from each joint limit [rad] ([m] prismatic)
  std::uint64_t seed = 1;            ///< restarts' random stream
};

/// Where the effector should be: relative to a point fixed to the target link.
struct TouchTarget {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    ///< x [m, target link frame]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< n, outward [unit, link frame]
  /// t [link frame], made orthogonal to n; zero: the effector's roll about its axis is free.
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
  double tilt = 0.0;      ///< θ [rad]: the axis leans from −n toward t (0 without a tangent)
  double distance = 0.0;  ///< d [m] along n (negative: pressed into the surface)
  /// Per-target overrides of TouchIkOptions (<= 0: the option's value): e.g. a looser axis far
  /// from the skin, where only the fingertip's path matters.
  double axis_tolerance = 0.0;  ///< [rad], also the roll tolerance
  double axis_weight = 0.0;     ///< [m]
  /// How much more it costs to move the target link's dofs than the effector's (>= 1): e.g.
  /// 100 keeps the touched limb still wherever the effector's arm alone can do the job.
  double target_dof_cost = 1.0;
};

struct TouchIkResult {
  bool success = false;
  double position_error = 0.0;  ///< |r_p| [m]
  double axis_error = 0.0;      ///< angle between the effector axis and a* [rad]
  double roll_error = 0.0;      ///< angle between the effector side and s* [rad] (0: no tangent)
  int iterations = 0;           ///< over all attempts
};

class TouchIk {
 public:
  /// `effector`: the touching frame (its origin is the contact point); `effector_axis` and
  /// `effector_side`: directions in the effector link frame (side may be zero when no target
  /// sets a tangent). `target_link`: the touched link. The solved dofs are those
  /// moving exactly one of the two links; the shared ones (and `held_dofs`) keep their values.
  /// InputError when a link index is invalid, an axis is zero, or no dof moves either link.
  TouchIk(std::shared_ptr<const robot::RobotModel> model, robot::FrameRef effector,
          const Eigen::Vector3d& effector_axis, const Eigen::Vector3d& effector_side,
          int target_link, const std::vector<int>& held_dofs = {}, TouchIkOptions options = {});

  /// Solves for `target`; `q` (full model vector) is the initial guess in, the solution out
  /// (within the limits; the best found when not successful). `home` (full vector): the
  /// posture regularisation target and the restart centre. InputError on wrong sizes.
  TouchIkResult solve(const TouchTarget& target, const Eigen::VectorXd& home, Eigen::VectorXd& q);

  /// Residual errors of `q` for `target` (no solving).
  TouchIkResult evaluate(const TouchTarget& target, const Eigen::VectorXd& q);

  /// Model dof indices of the solved dofs: the effector branch first, then the target branch.
  const std::vector<int>& solved_dofs() const { return dofs_; }
  /// How many of solved_dofs() move the effector (the rest move the target link).
  int effector_dofs() const { return effector_dofs_; }
  const robot::RobotModel& model() const { return *model_; }
  const TouchIkOptions& options() const { return options_; }
  const robot::FrameRef& effector() const { return effector_; }
  const Eigen::Vector3d& effector_axis() const { return effector_axis_; }  ///< link frame, unit
  const Eigen::Vector3d& effector_side() const { return effector_side_; }  ///< link frame
  int target_link() const { return target_link_; }

  /// Effector contact point and axis [root frame] at the last evaluated q.
  const Eigen::Vector3d& effector_point() const { return tip_; }
  const Eigen::Vector3d& effector_axis_root() const { return axis_; }

 private:
  // Forward kinematics at q, residual r_ (rows_) and, if wanted, its Jacobian on the solved dofs.
  double residual(const TouchTarget& target, const Eigen::VectorXd& q, bool jacobian);
  TouchIkResult errors() const;
  bool converged(const TouchIkResult& r, const TouchTarget& target) const;

  std::shared_ptr<const robot::RobotModel> model_;
  robot::FrameRef effector_;
  Eigen::Vector3d effector_axis_, effector_side_;
  int target_link_ = -1;
  TouchIkOptions options_;
  std::vector<int> dofs_;
  int effector_dofs_ = 0;
  Eigen::VectorXd lower_, upper_;  // solved dofs, with the margin
  robot::RobotData data_;
  robot::Matrix6Xd j_effector_, j_target_;
  Eigen::Matrix<double, 9, Eigen::Dynamic> jacobian_;
  Eigen::Matrix<double, 9, 1> r_;
  int rows_ = 6;
  Eigen::Vector3d tip_ = Eigen::Vector3d::Zero(), axis_ = Eigen::Vector3d::UnitX();
  Eigen::Vector3d side_ = Eigen::Vector3d::UnitY();
  Eigen::Vector3d goal_ = Eigen::Vector3d::Zero(), axis_goal_ = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d side_goal_ = Eigen::Vector3d::Zero();
};

}  // namespace somasim::control
