#pragma once
// believed_kinematics: what the robot believes of its own body (Roncone et al. 2016, Learning
// peripersonal space representation through artificial skin for avoidance and reaching with whole
// body surface: the systematic offset of the learned PPS maps comes from the robot's kinematic
// model, not from the skin).
//
// Every tick: believed joint values q_b = q_true + joint_offsets_deg + N(0, encoder_noise_deg)
// (the noise on revolute joints only, drawn anew each tick), one forward kinematics pass with
// q_b, and the skin taxels re-posed on their links by it:
//   position = T_link(q_b) · positions_link,  normal = R_link(q_b) · normals_link  (root frame).
// With zero offsets and noise every output equals its input (up to FK round-off).
#include <memory>
#include <vector>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class BelievedKinematics : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string joint_offsets_deg;   // "joint: value, ..." [deg] (prismatic [m])
    double encoder_noise_deg = 0.0;  // [deg]
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    In<JointState> true_state;
    OptionalIn<SkinTaxels> true_taxels;
    Out<JointState> state;
    Out<LinkPoses> link_poses;
    Out<SkinTaxels> taxels;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;

 private:
  void pose_taxels();

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<robot::RobotData> data_;
  Eigen::VectorXd offsets_;                   // per dof [rad] / [m]
  std::vector<double> noise_sigma_;           // per dof [rad] (0 for prismatic joints)
  std::vector<int> part_links_;               // link index per taxels part (cached by name)
  std::vector<std::string> part_link_names_;  // the names they were resolved from
  Ports ports_;
};

}  // namespace somasim::plugins
