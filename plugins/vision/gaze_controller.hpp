#pragma once
// gaze_controller: neck and eyes follow a stimulus (e.g. marker_tracker.stimulus) so that it
// stays in the middle of both images; position commands within the joint limits, at a bounded
// joint speed; targets out of reach are clamped and reported. Without a target (after hold_s)
// the gaze goes to an idle behaviour that uses only what the robot believes of its own body:
// hold (stay), fixation (the middle of the believed skin parts) or scan (each believed part in
// turn for dwell_s); never the stimulus's ground truth.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/vision/gaze.hpp"

namespace somasim::plugins {

/// What the gaze does without a target.
enum class GazeIdle : std::uint8_t { kHold, kFixation, kScan };
/// "hold", "fixation", "scan".
inline constexpr NamedValue<GazeIdle> kGazeIdleNames[] = {
    {GazeIdle::kHold, "hold"}, {GazeIdle::kFixation, "fixation"}, {GazeIdle::kScan, "scan"}};
constexpr std::span<const NamedValue<GazeIdle>> name_table(GazeIdle) {
  return kGazeIdleNames;
}

class GazeController : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> cameras{"left_eye", "right_eye"};
    std::vector<std::string> neck_joints{"neck_pitch", "neck_yaw"};
    std::vector<std::string> eye_joints{"eyes_tilt", "l_eye_pan", "r_eye_pan"};
    std::string joint_offsets_deg;
    double max_speed_deg_s = 60.0;  // [deg/s]
    double eye_centring = 0.05;
    double reach_tolerance_deg = 0.5;  // [deg]
    GazeIdle idle = GazeIdle::kHold;
    std::vector<std::string> idle_parts;
    double hold_s = 0.5;   // [s]
    double dwell_s = 2.0;  // [s]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<pps::Stimulus> target;
    OptionalIn<SkinTaxels> taxels;
    In<JointState> joint_state;
    Out<JointCommand> command;
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
  /// The believed centroid [m, root] of each idle part's taxels; false when a part is missing.
  bool part_centroids(std::vector<Eigen::Vector3d>& out) const;
  /// Aims goal_ at `point` (root frame); counts and logs out-of-reach targets when `tracking`.
  void aim(NodeContext& ctx, const Eigen::VectorXd& q, const Eigen::Vector3d& point, bool tracking);

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<vision::GazeSolver> solver_;
  Eigen::VectorXd offsets_;
  double max_speed_ = 0.0;               // [rad/s]
  double reach_tolerance_ = 0.0;         // [rad]
  double hold_s_ = 0.0, dwell_s_ = 0.0;  // [s]
  const SkinTaxels* taxels_ = nullptr;   // believed taxels (idle fixation / scan)
  const pps::Stimulus* target_ = nullptr;
  const JointState* joints_ = nullptr;
  JointCommand* command_ = nullptr;
  Eigen::VectorXd goal_;  // encoder values the gaze joints head for
  bool started_ = false;
  bool out_of_reach_ = false;    // in the current out-of-reach episode (logged once)
  double last_target_s_ = -1e9;  // sim time of the last target [s]
  double idle_since_s_ = 0.0;    // sim time the idle behaviour began [s]
  bool idle_now_ = true;
  std::int64_t steps_ = 0, steps_with_target_ = 0, clamped_steps_ = 0, idle_steps_ = 0;
  std::int64_t idle_entries_ = 0;
  double max_offset_rad_ = 0.0;
};

}  // namespace somasim::plugins
