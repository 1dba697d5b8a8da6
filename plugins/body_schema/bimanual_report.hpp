#pragma once
// bimanual_report: the positioning error of the body-schema study's bimanual task (Vicente et
// al. 2016, Fig 13): both hands reach (two reach_controller nodes in step), their index
// fingertips should touch with the palms a given distance apart. From the world's true link
// poses: the fingertip gap (between the fingertip frames, and between the surfaces of the
// fingers those frames lie on) and the palm-distance error at the end of the open loop and of
// the closed loop of every movement.
#include <string>
#include <vector>

#include "somasim/body_schema/ports.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class BimanualReport : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> fingertips{"r_index_tip", "l_index_tip"};
    std::vector<std::string> palms{"r_palm", "l_palm"};
    double palm_distance = 0.12;  // [m]
    int open_loop_frames = 120;
    int closed_loop_frames = 50;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<LinkPoses> true_link_poses;
    In<ReachPhase> phase;
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
  std::shared_ptr<const robot::RobotModel> model_;
  robot::FrameRef tips_[2], palms_[2];
  const robot::Geometry* fingers_[2] = {nullptr, nullptr};  // the shapes the tips lie on
  int open_frames_ = 120, closed_frames_ = 50;
  const LinkPoses* poses_ = nullptr;
  const ReachPhase* phase_ = nullptr;
  std::vector<double> gap_open_, gap_closed_, palm_open_, palm_closed_;  // [mm]
  std::vector<double> surface_gap_open_, surface_gap_closed_;            // [mm]
};

}  // namespace somasim::plugins
