#pragma once
// ball_thrower: throws balls one at a time at chosen skin parts of the robot and checks, against
// the physics ground truth, that every ball touching a part produces a skin contact event there.
//
// For each throw a target part is drawn (cycling through `parts`), then a random taxel of that
// part; the ball starts `distance` away along a direction within `cone_deg` of the taxel's outward
// normal and flies ballistically (gravity included) so that, undisturbed, its surface reaches the
// taxel after `flight_time`. It is removed after `ball_lifetime`, then the next one follows.
#include <map>
#include <memory>
#include <random>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class BallThrower : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::vector<std::string> parts{"left_forearm", "right_palm"};
    int throws = 40;
    double distance = 0.25;      // [m]
    double cone_deg = 40.0;      // [deg]
    double flight_time = 0.35;   // [s]
    double ball_lifetime = 1.0;  // [s]
    double ball_radius = 0.02;   // [m]
    double ball_mass = 0.05;     // [kg]
    double gravity = -9.81;      // [m/s^2]
    double skin_margin = 0.01;   // [m]
    double event_window = 0.2;   // [s]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<SkinTaxels> taxels;
    In<LinkPoses> link_poses;
    In<ObjectStates> objects;
    In<Contacts> contacts;
    In<ContactEvents> skin_events;
    Out<ObjectSpawns> spawns;
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
  struct Throw {
    std::string name, part;
    int part_link = -1;
    double t_spawn = 0.0;
    bool touched_part = false;       // touched the aimed part's link
    bool touched_part_skin = false;  // ... on its skin (near one of its taxels)
    bool touched_skin = false;       // touched the skin of any part
    bool event_on_part = false;
    double first_touch = -1.0;
    double max_force = 0.0;  // largest normal force on the aimed part's link [N]
  };
  void launch(NodeContext& ctx);
  void observe();
  bool near_skin(const std::string& part, const Eigen::Vector3d& point_root) const;
  void close_throw(NodeContext& ctx);

  std::shared_ptr<const robot::RobotModel> model_;
  double distance_ = 0, cone_rad_ = 0, flight_time_ = 0, lifetime_ = 0, radius_ = 0, mass_ = 0;
  double gravity_ = -9.81, event_window_ = 0.2, skin_margin_ = 0.02;
  double last_contact_time_ = -1e300;
  const SkinTaxels* skin_ = nullptr;
  const LinkPoses* link_poses_ = nullptr;
  const ObjectStates* objects_ = nullptr;
  const Contacts* contacts_ = nullptr;
  const ContactEvents* events_ = nullptr;
  ObjectSpawns* spawns_ = nullptr;
  Throw current_;
  bool active_ = false;
  int thrown_ = 0, hit_skin_ = 0, touched_expected_link_ = 0, touched_expected_ = 0;
  int hits_on_expected_ = 0, wrong_part_events_ = 0;
  std::uint64_t last_event_id_ = 0, next_spawn_id_ = 1;
  std::map<std::string, int> per_part_thrown_, per_part_hits_;
};

}  // namespace somasim::plugins
