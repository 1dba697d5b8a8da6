#pragma once
// pps_controller: exploitation of a learned peripersonal space (issue 4; Roncone et al. 2016,
// Learning peripersonal space representation through artificial skin for avoidance and reaching
// with whole body surface). Taxels of one body part (picked by label from a possibly multi-part
// activations input) whose activation exceeds `threshold` vote a point P and a normal N
// (activation-weighted, root frame); control::CartesianVelocityController moves that point of
// the arm at `speed` along −N (avoid) or +N (reach). Keeps moving `persistence` s after the last
// above-threshold tick, returns to the start posture (joint space) `return_after` s after it,
// and never carries any point of the body part farther than `workspace_radius` from where it was
// at the home posture: at the limit the joint velocities are scaled down (WorkspaceGuard), so the
// arm slides along the boundary or stops there, and only motion back inside is allowed. With
// `hold_orientation` the part's link is also asked not to turn (a 6-row task): the whole part,
// and the hand next to a forearm, then moves as the voted point does.
#include <memory>
#include <span>
#include <string>

#include "somasim/config.hpp"
#include "somasim/control/cartesian_velocity.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/pps/held_trigger.hpp"
#include "somasim/pps/part_activations.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "workspace_guard.hpp"

namespace somasim::plugins {

/// What the controller does with the voted point: move it away or toward.
enum class PpsMode : std::uint8_t { kAvoid, kReach };
/// "avoid", "reach".
inline constexpr NamedValue<PpsMode> kPpsModeNames[] = {{PpsMode::kAvoid, "avoid"},
                                                        {PpsMode::kReach, "reach"}};
constexpr std::span<const NamedValue<PpsMode>> name_table(PpsMode) {
  return kPpsModeNames;
}

/// Which way reaching moves the voted point: along +N or toward the perceived stimulus.
enum class ReachDirection : std::uint8_t { kNormal, kStimulus };
/// "normal", "stimulus".
inline constexpr NamedValue<ReachDirection> kReachDirectionNames[] = {
    {ReachDirection::kNormal, "normal"}, {ReachDirection::kStimulus, "stimulus"}};
constexpr std::span<const NamedValue<ReachDirection>> name_table(ReachDirection) {
  return kReachDirectionNames;
}

class PpsController : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string chain;
    std::string base;
    PpsMode mode = PpsMode::kAvoid;
    ReachDirection reach_direction = ReachDirection::kNormal;
    std::string body_part;
    double threshold = 0.4;
    double speed = 0.10;          // [m/s]
    double trigger_hold_s = 0.0;  // [s]
    double trigger_at_once_above = 1.0;
    double persistence = 0.3;                          // [s]
    double return_after = 1.0;                         // [s]
    double workspace_radius = 0.2;                     // [m]
    double return_gain = 2.0;                          // [1/s]
    double return_tolerance_deg = 0.1;                 // [deg]
    std::vector<double> max_joint_velocity_deg{60.0};  // [deg/s]
    double limit_margin_deg = 2.0;                     // [deg]
    bool hold_orientation = false;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<SkinTaxels> taxels;
    In<TaxelValues> activations;
    In<JointState> state;
    OptionalIn<pps::Stimulus> stimulus;
    Out<JointCommand> command;
    Out<Eigen::Vector3d> point;
    Out<Eigen::Vector3d> velocity;
    Out<double> triggered;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  const SkinPart& find_part(NodeContext& ctx);
  void hold(const Eigen::VectorXd& q);
  void move(NodeContext& ctx, const Eigen::VectorXd& q);
  void return_home(const Eigen::VectorXd& q, double period_s);

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<control::CartesianVelocityController> controller_;
  /// Holds every taxel of the part within workspace_radius of its home position (first step).
  std::unique_ptr<WorkspaceGuard> guard_;
  /// The guard looks this many control periods ahead (the joints follow with a lag).
  static constexpr double kGuardHorizonTicks = 2.0;
  /// The guard keeps the points this far [m] inside `workspace_radius`: the arm's servos lag
  /// its commands and a position hold sags a little under gravity, so the margin keeps the real
  /// arm (not just its commands) within the radius.
  static constexpr double kGuardMargin = 2e-3;
  std::unique_ptr<robot::RobotData> data_, home_data_;  ///< at q; at the start posture
  bool reach_ = false;
  double threshold_ = 0.4, speed_ = 0.1, persistence_ = 0.3, return_after_ = 1.0;
  double radius_ = 0.2, return_gain_ = 2.0, return_tolerance_ = 0.0;
  Eigen::VectorXd max_joint_velocity_;  ///< per chain dof [rad/s]

  const SkinTaxels* taxels_ = nullptr;
  const TaxelValues* activations_ = nullptr;
  /// The perceived stimulus, when reaching toward it (reach_direction: stimulus); else null.
  const pps::Stimulus* stimulus_ = nullptr;
  /// Closer than this to P, the stimulus gives no direction: +N is used [m].
  static constexpr double kMinAimDistance = 1e-3;
  pps::PartActivations part_activations_;
  const JointState* state_ = nullptr;
  JointCommand* command_ = nullptr;
  Eigen::Vector3d* point_ = nullptr;
  Eigen::Vector3d* velocity_ = nullptr;
  double* triggered_ = nullptr;

  int link_ = -1;  ///< the link of the body part's skin
  bool have_home_ = false;
  Eigen::VectorXd home_q_;
  bool have_target_ = false;  ///< a voted point/direction to move (until persistence ends)
  Eigen::Vector3d point_link_ = Eigen::Vector3d::Zero(), direction_ = Eigen::Vector3d::Zero();
  double last_trigger_s_ = 0.0;
  pps::HeldTrigger trigger_;    ///< the vote held for trigger_hold_s
  double at_once_above_ = 1.0;  ///< an activation above this votes without the hold
  bool was_triggered_ = false;
  bool away_from_home_ = false;  ///< moved since the last return home

  long triggers_ = 0, triggered_ticks_ = 0;
  double max_distance_ = 0.0;
  std::size_t outside_ticks_ = 0;
  bool holding_ = false;  ///< holding still at hold_q_ (position mode)
  Eigen::VectorXd hold_q_;
  /// A guard scale below this means the part is at the boundary: the arm holds there.
  static constexpr double kBlockedScale = 1e-3;  ///< control ticks with a point beyond the radius
  static constexpr double kOutsideTolerance = 1e-3;  ///< [m]
};

}  // namespace somasim::plugins
