#pragma once
/// @file
/// Damped-least-squares inverse kinematics on a KinematicChain (Levenberg–Marquardt damping,
/// joint limits enforced by clamping with an active set: a joint at a limit whose step would push
/// it further is frozen for that step). Deterministic restarts from random joint values within the
/// limits when a run stalls. Buffers are allocated once, in the constructor.
///
/// Frames: targets are in the chain's base frame (root frame for root chains). Units: [m], [rad].
#include <cstdint>

#include <Eigen/Geometry>

#include "somasim/robot/kinematic_chain.hpp"

namespace somasim::robot {

struct IkOptions {
  int max_iterations = 200;             ///< per attempt
  int restarts = 10;                    ///< extra attempts from random joint values
  double position_tolerance = 1e-4;     ///< [m]
  double orientation_tolerance = 1e-3;  ///< [rad]
  double orientation_weight = 0.3;      ///< [m/rad]: weight of rotation errors against position
  double initial_damping = 1e-2;        ///< λ of (J Jᵀ + λ² I)
  double max_step = 0.3;                ///< largest joint change per iteration [rad]
  std::uint64_t seed = 1;               ///< restarts' random stream
};

struct IkResult {
  bool success = false;
  double position_error = 0.0;     ///< [m]
  double orientation_error = 0.0;  ///< [rad]; 0 for position-only targets
  int iterations = 0;              ///< over all attempts
};

class IkSolver {
 public:
  explicit IkSolver(const KinematicChain& chain, IkOptions options = {});

  /// Moves the chain tip's origin to `target` [m]. q: initial guess in, solution out (always
  /// within the limits; the best found when not successful).
  IkResult solve_position(const Eigen::Vector3d& target, Eigen::Ref<Eigen::VectorXd> q);
  /// Moves the tip frame to `target` (position and orientation).
  IkResult solve_pose(const Eigen::Isometry3d& target, Eigen::Ref<Eigen::VectorXd> q);

  const IkOptions& options() const { return options_; }

 private:
  IkResult solve(const Eigen::Isometry3d& target, bool with_orientation,
                 Eigen::Ref<Eigen::VectorXd> q);
  double error(const Eigen::Isometry3d& target, const Eigen::Isometry3d& tip, bool with_orientation,
               Eigen::Matrix<double, 6, 1>& e) const;

  const KinematicChain& chain_;
  IkOptions options_;
  Matrix6Xd jacobian_;
  Eigen::VectorXd q_try_, q_best_, dq_;
  std::vector<bool> frozen_;
};

}  // namespace somasim::robot
