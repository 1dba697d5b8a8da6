#pragma once
/// @file
/// Gaze: the head and eye joint values that centre a point in both eyes' images (the point on
/// both optical axes), within the joint limits.
///
/// The solve is a damped Gauss-Newton on the angular offsets of the point from each camera's
/// optical axis (atan(x / z), atan(y / z) in each camera frame), over the gaze joints, first with
/// a weak pull of the eye joints toward 0 (the neck does the coarse pointing, the eyes the rest),
/// then without it, every iterate clamped to the limits. Angles [rad], points [m], root frame.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/robot/robot_model.hpp"

namespace somasim::vision {

struct GazeOptions {
  std::vector<std::string> neck_joints = {"neck_pitch", "neck_yaw"};
  std::vector<std::string> eye_joints = {"eyes_tilt", "l_eye_pan", "r_eye_pan"};
  std::vector<std::string> cameras = {"left_eye", "right_eye"};
  double eye_centring = 0.05;  ///< weight of the eyes' pull toward 0 (vs the image offsets)
  int iterations = 30;         ///< with the pull, then as many without it
};

struct GazeSolution {
  Eigen::VectorXd q;                  ///< all dofs: the input q with the gaze joints solved [rad]
  double residual_rad = 0.0;          ///< largest angular offset of the point from an optical axis
  std::vector<std::string> at_limit;  ///< gaze joints left at a limit (the point out of reach)
  bool behind = false;                ///< the point is behind a camera at the solution
};

class GazeSolver {
 public:
  /// Throws somasim::InputError naming a joint or camera that the model does not have:
  /// "gaze: robot 'R': ..." (the model's own message).
  GazeSolver(std::shared_ptr<const robot::RobotModel> model, GazeOptions options = {});

  /// The gaze joints (neck, then eyes) that look at `target_root`, starting from `q` (all
  /// dofs; the other joints are kept).
  GazeSolution solve(const Eigen::VectorXd& q, const Eigen::Vector3d& target_root) const;

  const std::vector<int>& dofs() const { return dofs_; }  ///< neck then eye dofs

 private:
  Eigen::VectorXd residual(const Eigen::VectorXd& q, const Eigen::Vector3d& target, double centring,
                           bool& behind) const;
  std::shared_ptr<const robot::RobotModel> model_;
  GazeOptions options_;
  std::vector<int> dofs_;
  int neck_count_ = 0;
};

}  // namespace somasim::vision
