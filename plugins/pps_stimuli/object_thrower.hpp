#pragma once
// object_thrower: the experimenter's stand-in for PPS learning with objects (PAPERS.md A, exp. 3).
//
// One approach at a time: a part is drawn (cycling through `parts`), then a random taxel of it; a
// kinematic object (cycling through `shapes`) starts `distance_min..max` from the taxel, within
// `cone` of its outward normal, and moves at a constant speed in `speed_min..max` so that its
// surface reaches the taxel after the travel time; the world removes it shortly after.
//
// `truth` is the object's centre and velocity (root frame) read back from the world. `stimulus`
// is what the robot perceives: the truth plus Gaussian noise, expressed through the believed
// kinematics of the aimed part's link (true joint values + `joint_offsets_deg`):
//   p_perceived = T_link_believed · T_link_true⁻¹ · p_noisy,  v_perceived = R_b · R_tᵀ · v_noisy.
#include <map>
#include <memory>
#include <random>

#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/robot_ports.hpp"

namespace somasim::plugins {

class ObjectThrower : public Plugin {
 public:
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  struct Approach {
    std::string name, part;
    int link = -1;
    Eigen::Vector3d taxel = Eigen::Vector3d::Zero();    // aimed taxel, root frame
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // its outward normal, root frame
    double t_spawn = 0.0, travel = 0.0, lifetime = 0.0;
    bool contact_seen = false;
  };
  void launch(NodeContext& ctx);
  void perceive(NodeContext& ctx);

  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<robot::RobotData> true_data_, believed_data_;
  Eigen::VectorXd offsets_;
  std::vector<std::string> parts_;
  std::vector<ObjectShape> shapes_;
  double size_ = 0, distance_min_ = 0, distance_max_ = 0, cone_rad_ = 0, speed_min_ = 0,
         speed_max_ = 0, pause_ = 0, linger_ = 0, position_noise_ = 0, velocity_noise_ = 0;
  int approaches_ = 0;
  const SkinTaxels* skin_ = nullptr;
  const JointState* state_ = nullptr;
  const ObjectStates* objects_ = nullptr;
  const LinkPoses* link_poses_ = nullptr;  // optional
  ObjectSpawns* spawns_ = nullptr;
  Stimulus* stimulus_ = nullptr;
  Stimulus* truth_ = nullptr;
  Approach current_;
  bool active_ = false;
  int launched_ = 0;
  std::uint64_t next_spawn_id_ = 1;
  std::map<std::string, double> contact_d_sum_;
  std::map<std::string, int> contact_d_count_, per_part_approaches_;
};

}  // namespace somasim::plugins
