#pragma once
// reach_controller: the body-schema study's reaching protocol (Vicente et al. 2016): per
// movement, go to a start posture, open loop (linear joint trajectory to the nominal IK solution
// of the desired palm pose), closed loop (position-based visual servoing with the adapted model
// K(θ + β̂)); evaluation against the truth. See README.md.
#include <memory>
#include <string>
#include <vector>

#include "reach_report.hpp"
#include "somasim/body_schema/eye_hand.hpp"
#include "somasim/body_schema/ports.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::plugins {

class ReachController : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string camera = "left_eye";
    std::string palm_frame = "r_palm";
    std::string arm_base = "chest";
    std::vector<double> targets;
    int starts_per_target = 10;
    int repetitions = 3;
    std::vector<double> start_distance{0.06, 0.12};  // [m]
    double start_rotation_deg = 15.0;
    int to_start_frames = 20;
    int open_loop_frames = 120;
    int closed_loop_frames = 50;
    double gain = 5.0;  // [1/s]
    bool adaptation = true;
    OutputFile csv{"reach_frames.csv", {}};
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<JointState> joint_state;
    OptionalIn<BodySchemaEstimate> estimate;
    OptionalIn<LinkPoses> true_link_poses;
    Out<JointCommand> command;
    Out<ReachPhase> phase;
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
  struct Target {
    Eigen::Isometry3d pose_eye;           // desired palm pose, left-eye frame
    Eigen::VectorXd posture;              // nominal IK solution (encoder values, all dofs)
    std::vector<Eigen::VectorXd> starts;  // start postures
  };
  void plan_targets(NodeContext& ctx, const Eigen::VectorXd& q0);
  Eigen::VectorXd draw_start(NodeContext& ctx, const Target& target, int index);
  MovementId movement_id(int movement) const;
  void begin_movement(int movement);
  void command(const Eigen::VectorXd& q);
  void evaluate(int frame);
  Eigen::VectorXd adapted_offsets() const;

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<body_schema::EyeHand> eye_hand_;
  std::vector<Target> targets_;
  int starts_per_target_ = 10, repetitions_ = 3;
  int to_start_frames_ = 20, open_frames_ = 120, closed_frames_ = 50;
  int visible_margin_px_ = 30;

  const JointState* joint_state_ = nullptr;
  const BodySchemaEstimate* estimate_ = nullptr;
  const LinkPoses* true_poses_ = nullptr;
  JointCommand* command_ = nullptr;
  ReachPhase* phase_ = nullptr;

  int movement_ = -1, movements_ = 0;
  bool movement_done_ = false;  // begin the next movement at the next tick
  int frame_ = 0;               // within the stage kToStart, then 1..open+closed
  Eigen::VectorXd from_, goal_;
  std::unique_ptr<ReachReport> report_;
  std::string csv_name_;
  std::filesystem::path csv_path_;
};

}  // namespace somasim::plugins
