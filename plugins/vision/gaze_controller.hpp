#pragma once
// gaze_controller: neck and eyes follow a stimulus (e.g. marker_tracker.stimulus) so that it
// stays in the middle of both images; position commands within the joint limits, at a bounded
// joint speed; targets out of reach are clamped and reported.
#include <memory>
#include <string>

#include <Eigen/Core>

#include "somasim/plugin.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/vision/gaze.hpp"

namespace somasim::plugins {

class GazeController : public Plugin {
 public:
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<vision::GazeSolver> solver_;
  Eigen::VectorXd offsets_;
  double max_speed_ = 0.0;        // [rad/s]
  double reach_tolerance_ = 0.0;  // [rad]
  const pps::Stimulus* target_ = nullptr;
  const JointState* joints_ = nullptr;
  JointCommand* command_ = nullptr;
  Eigen::VectorXd goal_;  // encoder values the gaze joints head for
  bool started_ = false;
  bool out_of_reach_ = false;  // in the current out-of-reach episode (logged once)
  std::int64_t steps_ = 0, steps_with_target_ = 0, clamped_steps_ = 0;
  double max_offset_rad_ = 0.0;
};

}  // namespace somasim::plugins
