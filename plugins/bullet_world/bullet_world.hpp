#pragma once
/// @file
/// The `bullet_world` plugin: the robot as a Bullet btMultiBody with a fixed base, joint motors,
/// gravity, self-collision, objects and contacts; one fixed physics step per tick.
///
/// Time: step(t) advances the world from t to t + period; the outputs then hold the state at
/// t + period (start() publishes the state at t = 0). Deterministic: no wall clock, single
/// thread, fixed insertion order.
///
/// Motors (see joint_motors.hpp): a position step settles within 2 % in 4/position_gain
/// (0.1 s at the default 40 /s) while the torque bound is not reached; documented settling time
/// at the default gains: 0.15 s for steps up to 0.5 rad of any arm joint (tested).
///
/// `locked_joints` fixes joints at their initial value: they are folded into rigid bodies (no
/// dynamics, no motor; commands on them are a RunError); with `all` the robot is static
/// collision geometry that still reports link poses, a constant joint state and contacts.
/// `joint_motion: kinematic` moves the joints that are not locked exactly as commanded (at most
/// max_joint_speed): no multibody, each rigid group a kinematic body posed by forward
/// kinematics; objects it meets are pushed by the solver (contact forces from its impulses), and
/// the robot does not yield. Kinematic objects touch immovable robot geometry (locked links, the
/// fixed base, kinematic links) too, and kinematic links touch static objects and other links:
/// the solver ignores such pairs (both bodies immovable), so their contacts carry a penetration
/// force, kinematic_contact_stiffness × depth. `kinematic_joints` mixes the two: the listed joints
/// (a kinematic joint's subtree holds only kinematic or locked joints) move so, the others stay
/// a multibody that the kinematic groups push as objects are pushed.
///
/// `joint_servo: computed_torque` drives a dynamic robot by joint torques from its inverse
/// dynamics instead of motor constraints (joint_motors.hpp): several times faster, with the
/// tracking error reported beside the speed in docs/performance.md.
///
/// Guided objects (object_manager.hpp: ObjectGuide) are dynamic bodies pulled along their path
/// by at most guide_max_force: what they meet stops them, so a link they press on feels a
/// bounded force instead of a prescribed motion. A blow-up that still happens names the bodies
/// in contact at that step.
#include <memory>
#include <set>
#include <vector>

#include "blowup_detector.hpp"
#include "collision_shapes.hpp"
#include "joint_motors.hpp"
#include "object_manager.hpp"
#include "physics_world.hpp"
#include "robot_multibody.hpp"
#include "self_collision_filter.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::bullet_world {

/// Documented settling time (2 % band) of a position step at the default gains [s].
inline constexpr double kDefaultSettlingTime = 0.15;

class BulletWorld : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    std::string initial_posture_deg;
    std::string encoder_offsets_deg;
    std::vector<std::string> locked_joints;
    JointMotion joint_motion = JointMotion::kDynamic;
    std::vector<std::string> kinematic_joints;
    JointServo joint_servo = JointServo::kConstraint;
    std::vector<double> gravity{0, 0, -9.81};  // [m/s^2]
    double position_gain = 40.0;               // [1/s]
    double velocity_gain = 1.0;
    double max_torque = 20.0;  // [N*m]
    int solver_iterations = 20;
    InputFile scene;
    double friction = 0.8;
    double rolling_friction = 0.0005;  // [m]
    double restitution = 0.0;
    double contact_distance = 0.0005;             // [m]
    double kinematic_contact_stiffness = 1000.0;  // [N/m]
    double guide_max_force = 5.0;                 // [N]
    double guide_bandwidth = 100.0;               // [1/s]
    double guide_contact_stiffness = 1000.0;      // [N/m]
    double contact_history = 0.1;                 // [s]
    double spawn_tolerance = 0.001;               // [m]
    double world_radius = 10.0;                   // [m]
    double max_joint_speed = 99.0;                // [rad/s]
    double max_object_speed = 50.0;               // [m/s]
    double max_penetration = 0.02;                // [m]
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    OptionalIn<JointCommand> commands;
    OptionalIn<ObjectSpawns> spawns;
    Out<JointState> joint_state;
    Out<LinkPoses> link_poses;
    Out<ObjectStates> objects;
    Out<Contacts> contacts;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void start(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  void spawn_from_port(NodeContext& ctx, double t);
  void publish(double t);
  /// The commands with position targets shifted from encoder to real values (encoder offsets).
  const JointCommand& real_commands(const JointCommand& commands);

  // Declaration order = reverse destruction order: bodies go before shapes, filter and world.
  std::shared_ptr<const robot::RobotModel> model_;
  std::unique_ptr<PhysicsWorld> physics_;
  std::unique_ptr<SelfCollisionFilter> filter_;
  std::unique_ptr<ShapeStore> shapes_;
  std::unique_ptr<RobotMultiBody> robot_;
  std::unique_ptr<JointMotors> motors_;
  std::unique_ptr<ObjectManager> objects_;

  double dt_ = 1e-3;
  BlowupLimits limits_;
  std::set<std::uint64_t> seen_spawns_;

  JointState* joint_state_ = nullptr;
  LinkPoses* link_poses_ = nullptr;
  ObjectStates* object_states_ = nullptr;
  Contacts* contacts_ = nullptr;
  const JointCommand* commands_ = nullptr;
  // Miscalibrated encoders (encoder_offsets_deg): readings = real - offsets [rad].
  Eigen::VectorXd encoder_offsets_;
  bool miscalibrated_ = false;
  JointCommand real_commands_;  // commands shifted to real joint values, reused

  const ObjectSpawns* spawns_ = nullptr;

  // Metrics.
  std::int64_t steps_ = 0;
  std::int64_t contact_points_ = 0;
  std::int64_t max_contact_points_ = 0;
  double max_penetration_ = 0.0;
  std::int64_t objects_spawned_ = 0;
  std::int64_t objects_out_of_bounds_ = 0;
  std::int64_t objects_withdrawn_ = 0;  // removed on request (spawns' `withdraw`)
};

}  // namespace somasim::bullet_world
