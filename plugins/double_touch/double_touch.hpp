#pragma once
// double_touch: tactile-motor PPS learning by self-touch (Roncone et al. 2016, Learning
// peripersonal space representation through artificial skin for avoidance and reaching with whole
// body surface, experiment 2). The right index fingertip touches chosen taxels of the left forearm,
// again and again, and is the stimulus the skin learns from, perceived through proprioception.
//
// Each touch: a taxel of `body_part` is drawn (at random among the reachable ones, or in turn
// from `taxels`), its point jittered along the skin (`position_jitter`) and its approach direction
// within `normal_jitter_deg` of the normal. control::TouchPlanner solves the postures for the
// fingertip at the point + d·n, d from `start_distance` down to −`press_depth` (finger along −n
// leaning `finger_tilt_deg` across the limb so that the longer middle finger stays off the skin,
// within `align_distance`; free to lean up to `max_tilt_deg` farther out; torso held): both arms
// present the limb, which then stays nearly still while the fingertip's arm follows the normal.
// Taxels that are unreachable or where the arms would come too close elsewhere are redrawn. The
// arms move (minimum jerk, joint space, `move_duration`) to the start of the approach, the
// fingertip closes in along the normal at a speed drawn in `speed_min..speed_max` (the
// interpolation between IK waypoints is solved for the exact distance), holds `hold` s, retreats at
// `speed_max`, and the next touch begins; after `touches` touches the arms return home and the
// run stops. Commands: position (with velocity feed-forward) on both arms' dofs.
//
// The stimulus is the fingertip as the robot perceives it: forward kinematics of the BELIEVED
// joint values (`believed_state`, else the true ones) + Gaussian `position_noise`; it is the ball
// inscribed in the fingertip (centre one finger radius behind the tip along the finger axis,
// radius = `finger_radius`), so D ≈ 0 when the fingertip touches the taxel. Velocity: finite
// difference of the noise-free perceived centre over the node period (differencing noisy
// positions would turn 1 mm of noise into ~0.1 m/s at 100 Hz), + `velocity_noise`. Present
// during the approach and the hold. `true_offsets`: see somasim/pps/true_offsets.hpp (the contact
// instant is taken where the fingertip reached the skin, as for objects).
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "somasim/config.hpp"
#include "somasim/control/touch_planner.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/pps/true_offsets.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

/// How the robot perceives its touching fingertip.
enum class FingertipPerception : std::uint8_t { kProprioception, kVision };
/// "proprioception", "vision".
inline constexpr NamedValue<FingertipPerception> kFingertipPerceptionNames[] = {
    {FingertipPerception::kProprioception, "proprioception"},
    {FingertipPerception::kVision, "vision"}};
constexpr std::span<const NamedValue<FingertipPerception>> name_table(FingertipPerception) {
  return kFingertipPerceptionNames;
}

class DoubleTouch : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string body_part = "left_forearm";
    std::string effector = "r_index_tip";
    std::vector<double> effector_axis{1, 0, 0};
    std::vector<double> effector_side{0, 1, 0};
    std::vector<double> limb_axis{0, 1, 0};
    double finger_tilt_deg = 25.0;  // [deg]
    double finger_radius = 0.0065;  // [m]
    std::vector<std::string> taxels;
    int touches = 20;
    // The planner's defaults (control::TouchPlannerOptions{}; max_tilt there in radians)
    double start_distance = planner_defaults().start_distance;  // [m]
    double press_depth = planner_defaults().press_depth;        // [m]
    double align_distance = planner_defaults().align_distance;  // [m]
    double max_tilt_deg = 60.0;                                 // [deg]
    double approach_step = planner_defaults().step;             // [m]
    double speed_min = 0.05;                                    // [m/s]
    double speed_max = 0.15;                                    // [m/s]
    double position_jitter = 0.003;                             // [m]
    double normal_jitter_deg = 5.0;                             // [deg]
    // A double-touch posture of the iCub: the left forearm in front of the body, turned
    // (prosup) so that most of its skin faces the right hand, the right hand beside it (21 of
    // the 32 forearm taxels of icub_v1 can then be touched).
    std::string home_posture_deg =
        "l_shoulder_pitch: -60, l_shoulder_roll: 30, l_shoulder_yaw: 30, l_elbow: 55, "
        "l_wrist_prosup: -45, r_shoulder_pitch: -45, r_shoulder_roll: 30, r_shoulder_yaw: 30, "
        "r_elbow: 70";
    double move_duration = 2.0;                       // [s]
    double hold = 0.3;                                // [s]
    double clearance = planner_defaults().clearance;  // [m]
    double position_noise = 0.0;                      // [m]
    double velocity_noise = 0.0;                      // [m/s]
    FingertipPerception perception = FingertipPerception::kProprioception;
    double marker_radius = 0.007;  // [m]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
    static constexpr control::TouchPlannerOptions planner_defaults() { return {}; }
  };
  struct Ports {
    In<JointState> state;
    In<SkinTaxels> taxels;
    OptionalIn<ContactEvents> contacts;
    OptionalIn<JointState> believed_state;
    OptionalIn<SkinTaxels> believed_taxels;
    Out<JointCommand> command;
    Out<pps::Stimulus> stimulus;
    Out<pps::Stimulus> truth;
    Out<TaxelValues> true_offsets;
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
  enum class Phase { kPlan, kTransfer, kApproach, kHold, kRetreat, kHome, kDone };
  struct Touch {
    int taxel_id = -1;
    double speed = 0.0;
    double t_approach = 0.0, t_end = 0.0;
    bool reached_skin = false;
    bool on_aimed_taxel = false;  // an event of the touch named the aimed taxel
    double final_error = -1.0;    // [m] true fingertip to aimed taxel at the end of the hold
  };

  const SkinPart& part(NodeContext& ctx) const;
  bool plan_touch(NodeContext& ctx);
  void start_transfer(double now, const Eigen::VectorXd& goal);
  void advance(NodeContext& ctx);
  void perceive(NodeContext& ctx);
  void read_contacts(NodeContext& ctx);
  void add_true_offsets(const ContactEvent& e);
  void write_command();

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<control::TouchPlanner> planner_;
  std::unique_ptr<robot::RobotData> true_data_, believed_data_;
  robot::FrameRef effector_;
  Eigen::Vector3d effector_axis_link_ = Eigen::Vector3d::UnitX();
  Eigen::Vector3d limb_axis_ = Eigen::Vector3d::UnitY();
  std::vector<int> taxel_list_;
  double finger_tilt_ = 0, speed_min_ = 0, speed_max_ = 0, position_jitter_ = 0, normal_jitter_ = 0;
  double move_duration_ = 0, hold_ = 0, finger_radius_ = 0, position_noise_ = 0,
         velocity_noise_ = 0;
  Eigen::VectorXd home_;

  const JointState* state_ = nullptr;
  const JointState* believed_state_ = nullptr;  // optional
  const SkinTaxels* taxels_ = nullptr;
  const SkinTaxels* believed_taxels_ = nullptr;  // optional
  const ContactEvents* contacts_ = nullptr;      // optional
  JointCommand* command_ = nullptr;
  pps::Stimulus* stimulus_ = nullptr;
  pps::Stimulus* truth_ = nullptr;
  TaxelValues* true_offsets_ = nullptr;

  // Motion.
  Phase phase_ = Phase::kPlan;
  bool started_ = false;
  Eigen::VectorXd q_ref_, dq_ref_;
  Eigen::VectorXd transfer_from_, transfer_to_;
  double phase_start_ = 0.0;
  control::TouchPath path_;
  int planned_taxel_ = -1;              // index into the part
  std::vector<std::size_t> reachable_;  // indices of the taxels reachable from home
  Eigen::Vector3d aimed_link_ = Eigen::Vector3d::Zero();          // aimed point, link frame
  Eigen::Vector3d aimed_normal_link_ = Eigen::Vector3d::UnitZ();  // approach direction (−)
  std::unique_ptr<robot::RobotData> plan_data_;
  std::function<double(const Eigen::VectorXd&)> measure_;  // planned distance at a posture

  // Perception.
  pps::Stimulus perceived_clean_;  // noise-free perceived stimulus of this tick
  pps::Stimulus truth_clean_;      // true stimulus of this tick (also when not presented)
  Eigen::Vector3d last_perceived_ = Eigen::Vector3d::Zero(), last_true_ = Eigen::Vector3d::Zero();
  bool seen_by_eyes_ = false;  // perception: vision
  bool have_last_ = false;
  std::deque<pps::PathSample> path_history_;  // the last pps::kOffsetMaxBackoff s (true offsets)
  pps::TrueOffsets offsets_;
  int true_offset_samples_ = 0;
  std::uint64_t last_event_id_ = 0;

  // Statistics.
  std::vector<Touch> log_;
  int ik_failures_ = 0, collision_rejections_ = 0, events_on_part_ = 0, events_elsewhere_ = 0,
      events_outside_touches_ = 0, next_in_list_ = 0;
};

}  // namespace somasim::plugins
