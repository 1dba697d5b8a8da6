#pragma once
/// @file
/// Plans one double touch. The limb is presented first: both arms are solved together (TouchIk,
/// regularised toward home) for the fingertip at a middle distance along the normal; the limb
/// then stays still and the effector's arm alone is solved for the approach postures, from there
/// out to `start_distance` and in to `press_depth` below the skin, each seeded by the previous one
/// (so the fingertip's root-frame velocity is its velocity relative to the skin, as the PPS
/// learner assumes). If that fails, the limb is presented for the touch itself, then for a far
/// point. Every posture, and the joint-space move to the start, is checked for clearance between
/// the two arms (and the trunk) apart from the touching finger on the touched link.
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/control/link_clearance.hpp"
#include "somasim/control/touch_ik.hpp"

namespace somasim::control {

struct TouchPlannerOptions {
  double start_distance = 0.20;  ///< [m]
  double press_depth = 0.003;    ///< [m] below the taxel at the end of the approach
  double step = 0.01;            ///< distance between IK waypoints [m]
  double clearance = 0.002;      ///< smallest distance between other shapes of the arms [m]
  int transfer_checks = 10;      ///< samples of the joint-space move to the start checked
  /// Within align_distance of the skin the finger is along −n (the IK's tolerance); farther out
  /// only the fingertip stays on the normal and the finger may tilt, up to max_tilt at
  /// start_distance (the arms cannot hold a 20 cm normal approach for every taxel).
  double align_distance = 0.03;                       ///< [m]
  double max_tilt = 60.0 * std::numbers::pi / 180.0;  ///< [rad]
  double far_axis_weight = 0.001;                     ///< IK axis weight beyond align_distance [m]
  /// Along the approach, moving the touched limb costs this much more than moving the effector's
  /// arm: the limb stays still wherever the arm alone can follow the normal.
  double limb_cost = 100.0;
  /// The fingertip may stray this far from the approach line between waypoints [m], and a
  /// joint may change at most max_joint_rate per metre; otherwise the segment is halved (a plan
  /// whose posture still jumps after max_refinements halvings is rejected).
  double path_tolerance = 0.001;
  double max_joint_rate = 25.0;  ///< largest joint change per metre of approach [rad/m]
  int max_refinements = 4;
};

/// The approach: postures (full model vectors) at decreasing distances.
struct TouchPath {
  std::vector<double> distance;          ///< along the target's normal [m], decreasing
  std::vector<Eigen::VectorXd> posture;  ///< full model vectors [rad, m], one per distance

  /// Posture at distance d (clamped to the path), piecewise linear; `dq_dd` (optional): its
  /// derivative with respect to d [rad/m].
  void sample(double d, Eigen::VectorXd& q, Eigen::VectorXd* dq_dd = nullptr) const;
  /// Same, but on each segment the interpolation parameter is solved (regula falsi) so that
  /// `measure(q)` — the effector's actual distance from the target along its normal — equals d:
  /// the fingertip then closes in at exactly the commanded rate between the IK waypoints.
  void sample(double d, const std::function<double(const Eigen::VectorXd&)>& measure,
              Eigen::VectorXd& q, Eigen::VectorXd* dq_dd = nullptr) const;
  double start() const { return distance.front(); }
  double end() const { return distance.back(); }
};

enum class PlanResult { kOk, kUnreachable, kCollision };

class TouchPlanner {
 public:
  TouchPlanner(std::shared_ptr<const robot::RobotModel> model, TouchIk ik,
               TouchPlannerOptions options);

  /// Plans an approach to `target` (its distance is ignored) starting with a joint-space move
  /// from `from`; `home` regularises the postures. `detail` says why a plan failed.
  PlanResult plan(const TouchTarget& target, const Eigen::VectorXd& home,
                  const Eigen::VectorXd& from, TouchPath& path, std::string& detail);

  TouchIk& ik() { return ik_; }
  const TouchPlannerOptions& options() const { return options_; }

 private:
  // The target at distance d (the finger may lean beyond align_distance).
  TouchTarget at(TouchTarget target, double d) const;
  // One approach posture at distance d (seeded by q; the limb kept as still as it can).
  bool solve_at(const TouchTarget& target, const Eigen::VectorXd& home, double d,
                Eigen::VectorXd& q, std::string& detail);
  // Appends q1 at d1 after q0 at d0, with midpoints where the interpolation strays.
  bool refine(const TouchTarget& target, const Eigen::VectorXd& home, double d0,
              const Eigen::VectorXd& q0, double d1, const Eigen::VectorXd& q1, int depth,
              TouchPath& path, std::string& detail);
  // Postures through distances `ds` from q at d_from; appends them (not d_from) to `path`.
  bool sweep(const TouchTarget& target, const Eigen::VectorXd& home, double d_from,
             const std::vector<double>& ds, Eigen::VectorXd q, TouchPath& path,
             std::string& detail);
  // Clearance of posture q [m] (and the closest pair in `detail`).
  double clearance(const Eigen::VectorXd& q, std::string* detail);

  std::shared_ptr<const robot::RobotModel> model_;
  TouchIk ik_;
  TouchPlannerOptions options_;
  std::unique_ptr<LinkClearance> check_;
  robot::RobotData data_;
};

}  // namespace somasim::control
