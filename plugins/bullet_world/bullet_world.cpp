#include "bullet_world.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "contact_extraction.hpp"
#include "contact_history.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/object_geometry.hpp"
#include "somasim/robot/scene_file.hpp"

namespace somasim::bullet_world {

template <class V>
void BulletWorld::Config::visit(V& v) {
  v.block(robot);
  v.field("initial_posture_deg", initial_posture_deg)
      .map_as_text()
      .doc(
          "initial joint values held by the motors, 'joint: value, ...' in degrees (prismatic: "
          "m); unlisted joints start at 0 clamped into their limits");
  v.field("encoder_offsets_deg", encoder_offsets_deg)
      .map_as_text()
      .doc(
          "miscalibrated encoders, 'joint: beta, ...' in degrees: the real joint values are the "
          "encoder readings plus beta (body-schema study). joint_state reports real - beta and "
          "position commands are encoder values (the motors drive real = command + beta); "
          "initial_posture_deg and link_poses are real");
  v.field("locked_joints", locked_joints)
      .doc(
          "joints fixed at their initial value (names, or 'all'): "
          "folded into rigid bodies, no dynamics and no motor; a command on them stops the run. "
          "With 'all' the robot is static collision geometry (fastest; contacts still reported)");
  v.field("joint_motion", joint_motion)
      .doc(
          "how the joints not locked move: dynamic (motors, limits, contacts push back) or "
          "kinematic (exactly as commanded, at most max_joint_speed; objects are pushed, the "
          "robot does not yield; contacts still reported with forces)");
  v.field("kinematic_joints", kinematic_joints)
      .doc(
          "with joint_motion: dynamic, joints moved kinematically (names, or 'all'): their groups "
          "follow the commands exactly as under joint_motion: kinematic while the rest stays "
          "dynamic. A kinematic joint's subtree holds only kinematic or locked joints; a group "
          "under moving dynamic joints is posed from their values before each step");
  v.field("joint_servo", joint_servo)
      .doc(
          "how a dynamic robot's joints are driven: constraint (Bullet motors solved with the "
          "contacts, firmest) or computed_torque (torques from the robot's inverse dynamics, "
          "each joint a critically damped servo at position_gain; several times faster, the "
          "solver left with contacts and limits)");
  v.field("gravity", gravity).size(3).unit("m/s^2").doc("gravity in the root frame");
  v.field("position_gain", position_gain)
      .unit("1/s")
      .range(0, 1e4)
      .doc(
          "motor position gain: target joint velocity = position_gain * (q* - q) + v*; a step "
          "settles (2%) in about 4/position_gain");
  v.field("velocity_gain", velocity_gain)
      .range(0, 1)
      .doc("motor velocity gain: weight of the velocity target (1 = track it exactly)");
  v.field("max_torque", max_torque)
      .unit("N*m")
      .range(0, 1e4)
      .doc("largest motor torque per joint (prismatic joints: N)");
  v.field("solver_iterations", solver_iterations)
      .range(1, 1000)
      .doc(
          "iterations of Bullet's constraint solver per step (the solver is most of a step's "
          "cost; below about 15 the motors no longer hold a ball's weight firmly)");
  v.field("scene", scene)
      .doc(
          "optional scene file with objects present from t = 0 (format in "
          "somasim/robot/scene_file.hpp), relative to the experiment file");
  v.field("friction", friction).range(0, 10).doc("friction coefficient of links and objects");
  v.field("rolling_friction", rolling_friction)
      .unit("m")
      .range(0, 1)
      .doc("rolling and spinning friction of objects (lets balls come to rest)");
  v.field("restitution", restitution).range(0, 1).doc("restitution of links and objects");
  v.field("contact_distance", contact_distance)
      .unit("m")
      .range(0, 0.1)
      .doc("contact points closer than this (or penetrating) are reported");
  v.field("kinematic_contact_stiffness", kinematic_contact_stiffness)
      .unit("N/m")
      .range(0, 1e7)
      .doc(
          "normal force per metre of penetration reported for a kinematic object touching "
          "immovable robot geometry (locked links, the fixed base), where the solver applies no "
          "force; the object keeps its path");
  v.field("guide_max_force", guide_max_force)
      .unit("N")
      .range(0, 1e4)
      .doc(
          "largest force that pulls a guided object along its path (a hand holding it): "
          "against the robot it presses with at most this much");
  v.field("guide_bandwidth", guide_bandwidth)
      .unit("1/s")
      .range(1, 1e4)
      .doc(
          "bandwidth of the critically damped servo that keeps a guided object on its path "
          "(keep bandwidth x step well below 1)");
  v.field("guide_contact_stiffness", guide_contact_stiffness)
      .unit("N/m")
      .range(0, 1e7)
      .doc(
          "contact stiffness of guided objects (0: rigid): pressed with F, a guided object sinks "
          "about F / stiffness into what it touches, as a held object into the soft skin "
          "(the same law as kinematic_contact_stiffness)");
  v.field("contact_history", contact_history)
      .unit("s")
      .range(0, 10)
      .doc(
          "contacts of this recent past are kept in the output's `recent` list, so that "
          "slower nodes (a 50 Hz skin) see brief impacts");
  v.field("spawn_tolerance", spawn_tolerance)
      .unit("m")
      .range(0, 1)
      .doc("an object may start overlapping a robot link by at most this much");
  v.field("world_radius", world_radius)
      .unit("m")
      .range(0.1, 1e6)
      .doc("dynamic objects farther than this from the root are removed (fell away)");
  v.field("max_joint_speed", max_joint_speed)
      .unit("rad/s")
      .range(0, 99)
      .doc(
          "blow-up bound: a faster joint stops the run (kept below Bullet's own clamp of joint "
          "speeds at 100 rad/s, which a blown-up joint sits at; hard contacts can briefly "
          "drive a light joint to ~70 rad/s)");
  v.field("max_object_speed", max_object_speed)
      .unit("m/s")
      .range(0, 1e6)
      .doc("blow-up bound: a faster object stops the run");
  v.field("max_penetration", max_penetration)
      .unit("m")
      .range(0, 10)
      .doc("blow-up bound: a deeper interpenetration stops the run");
}

template <class V>
void BulletWorld::Ports::visit(V& v) {
  v.port("commands", commands,
         "joint commands (position/velocity per dof; kNone keeps the last target)");
  v.port("spawns", spawns, "objects to add (each id once)");
  v.port("joint_state", joint_state, "joint positions [rad] and velocities [rad/s], dof order");
  v.port("link_poses", link_poses, "pose of every model link in the root frame, link order");
  v.port("objects", objects, "state of every object, spawn order (root frame)");
  v.port("contacts", contacts,
         "contact points of the last step: bodies, point (root and link-a frame), "
         "normal from b to a, normal force [N]");
}

PluginSpec BulletWorld::spec() {
  return make_plugin_spec<Config, Ports>(
      "bullet_world",
      "Physics (Bullet, double precision): the robot as a fixed-base btMultiBody with "
      "joint motors and limits, gravity, self-collision (adjacent links filtered), "
      "static/dynamic/kinematic/guided objects and contacts (a sphere touches a convex shape at "
      "one point per step). One fixed step per tick.");
}

void BulletWorld::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  Eigen::VectorXd q0;
  try {
    q0 = robot::parse_posture_deg(*model_, config_.initial_posture_deg);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.initial_posture_deg, e.what());
  }
  try {
    encoder_offsets_ = robot::parse_joint_offsets(*model_, config_.encoder_offsets_deg);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.encoder_offsets_deg, e.what());
  }
  miscalibrated_ = !encoder_offsets_.isZero();
  std::vector<bool> locked;
  try {
    locked = parse_joint_set(config_.locked_joints, *model_);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.locked_joints, e.what());
  }
  std::vector<bool> kinematic;
  try {
    if (config_.joint_motion == JointMotion::kKinematic && !config_.kinematic_joints.empty())
      throw InputError(
          "kinematic_joints needs joint_motion: dynamic (joint_motion: kinematic already moves "
          "every joint that is not locked kinematically)");
    // 'all' means every joint not locked, as joint_motion: kinematic does.
    const bool all = config_.joint_motion == JointMotion::kKinematic ||
                     std::find(config_.kinematic_joints.begin(), config_.kinematic_joints.end(),
                               "all") != config_.kinematic_joints.end();
    kinematic = kinematic_dofs(
        *model_, locked, all,
        all ? std::vector<bool>{} : parse_joint_set(config_.kinematic_joints, *model_));
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.kinematic_joints, e.what());
  }
  dt_ = ctx.period_s();
  limits_ = {config_.max_joint_speed, config_.max_object_speed, config_.max_penetration};
  const auto g = config_.gravity;
  const double friction = config_.friction;
  const double rolling = config_.rolling_friction;
  const double restitution = config_.restitution;

  physics_ =
      std::make_unique<PhysicsWorld>(Eigen::Vector3d(g[0], g[1], g[2]), config_.solver_iterations);
  filter_ = std::make_unique<SelfCollisionFilter>(*model_, locked);
  physics_->set_pair_filter(filter_.get());
  shapes_ = std::make_unique<ShapeStore>();
  try {
    robot_ = std::make_unique<RobotMultiBody>(model_, physics_->world(), *shapes_, q0,
                                              LinkMaterial{friction, 0.0, restitution}, locked,
                                              kinematic);
  } catch (const InputError& e) {  // e.g. a collision mesh that cannot be used
    robot::robot_error(ctx, e.what());
  }
  const MotorGains gains{config_.position_gain, config_.velocity_gain, config_.max_torque};
  if (config_.joint_servo == JointServo::kComputedTorque && config_.position_gain * dt_ > 0.25)
    config_error(ctx, config_, config_.position_gain,
                 fmt::format("{} 1/s at a {} s step makes the computed-torque servo unstable: "
                             "keep position_gain x step <= 0.25 (here <= {:g} 1/s)",
                             config_.position_gain, dt_, 0.25 / dt_));
  motors_ = std::make_unique<JointMotors>(*robot_, physics_->world(), gains, dt_, q0,
                                          config_.joint_servo, Eigen::Vector3d(g[0], g[1], g[2]));
  const ObjectGuide guide{config_.guide_max_force, config_.guide_bandwidth,
                          config_.guide_contact_stiffness};
  if (guide.bandwidth * dt_ > 0.5)
    config_error(ctx, config_, config_.guide_bandwidth,
                 fmt::format("{} 1/s at a {} s step makes the guide unstable: keep "
                             "guide_bandwidth x step <= 0.5 (here <= {:g} 1/s)",
                             guide.bandwidth, dt_, 0.5 / dt_));
  objects_ = std::make_unique<ObjectManager>(physics_->world(), *shapes_,
                                             ObjectMaterial{friction, rolling, restitution}, guide);
  physics_->world().updateAabbs();

  if (config_.scene.given()) {
    std::vector<robot::SceneObject> objects;
    try {
      objects = robot::load_scene(config_.scene.path);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.scene, e.what());
    }
    for (const robot::SceneObject& so : objects) {
      int i = -1;
      try {
        i = objects_->add(so.spawn, 0.0);
      } catch (const InputError& e) {  // e.g. a mesh that cannot be used
        config_error(ctx, config_, config_.scene,
                     fmt::format("{}: object '{}': {}", so.where.str(), so.spawn.name, e.what()));
      }
      const RobotOverlap overlap =
          deepest_robot_overlap(physics_->world(), *robot_, objects_->body(i));
      if (overlap.link >= 0 && overlap.depth > config_.spawn_tolerance)
        throw InputError(
            fmt::format("{}: object '{}' starts inside the robot: it overlaps link "
                        "'{}' by {:.1f} mm",
                        so.where.str(), objects_->name(i), model_->link(overlap.link).name,
                        overlap.depth * 1e3));
      ++objects_spawned_;
    }
  }

  joint_state_ = &ports_.joint_state.get();
  link_poses_ = &ports_.link_poses.get();
  object_states_ = &ports_.objects.get();
  contacts_ = &ports_.contacts.get();
  commands_ = ports_.commands.get();
  spawns_ = ports_.spawns.get();
}

void BulletWorld::start(NodeContext& ctx) {
  publish(ctx.time_s());
}

void BulletWorld::spawn_from_port(NodeContext& ctx, double t) {
  for (const ObjectSpawn& s : spawns_->recent) {
    if (!seen_spawns_.insert(s.id).second) continue;
    const std::string what =
        fmt::format("t = {:.3f} s: spawned object '{}' (id {})", t, s.name, s.id);
    if (const std::string problem = robot::spawn_problem(s); !problem.empty())
      throw RunError(what + ": " + problem);
    ObjectSpawn resolved = s;
    if (s.shape == ObjectShape::kMesh) resolved.mesh = ctx.resolve_input_path(s.mesh).string();
    int i = -1;
    try {
      i = objects_->add(resolved, t);
    } catch (const InputError& e) {
      throw RunError(what + ": " + e.what());
    }
    const RobotOverlap overlap =
        deepest_robot_overlap(physics_->world(), *robot_, objects_->body(i));
    if (overlap.link >= 0 && overlap.depth > config_.spawn_tolerance)
      throw RunError(fmt::format("{} starts inside the robot: it overlaps link '{}' by {:.1f} mm",
                                 what, model_->link(overlap.link).name, overlap.depth * 1e3));
    ++objects_spawned_;
  }
}

void BulletWorld::step(NodeContext& ctx) {
  const double t = ctx.time_s();
  if (commands_) motors_->apply(real_commands(*commands_), t);
  if (spawns_) {
    spawn_from_port(ctx, t);
    for (const std::string& name : spawns_->withdraw)
      objects_withdrawn_ += objects_->remove_named(name);
  }
  objects_->remove_expired(t);
  objects_->drive(t, dt_);
  // Kinematic joints: a hair below the blow-up detector's speed bound.
  if (robot_->any_kinematic()) motors_->advance_kinematic(0.999 * config_.max_joint_speed);
  motors_->update_limits();
  motors_->apply_torques();
  physics_->step(dt_);
  ++steps_;
  publish(t + dt_);
}

const JointCommand& BulletWorld::real_commands(const JointCommand& commands) {
  if (!miscalibrated_) return commands;
  real_commands_ = commands;
  for (std::size_t d = 0; d < commands.mode.size(); ++d)
    if (commands.mode[d] == JointCommandMode::kPosition)
      real_commands_.position[static_cast<Eigen::Index>(d)] +=
          encoder_offsets_[static_cast<Eigen::Index>(d)];
  return real_commands_;
}

void BulletWorld::publish(double t) {
  robot_->read_joint_state(*joint_state_);
  if (miscalibrated_) joint_state_->position -= encoder_offsets_;
  robot_->link_poses(link_poses_->poses);
  const Penetration deepest =
      extract_contacts(physics_->dispatcher(), *robot_, link_poses_->poses, *objects_, dt_,
                       config_.contact_distance, config_.kinematic_contact_stiffness, *contacts_);
  record_contact_history(*contacts_, t, config_.contact_history);
  max_penetration_ = std::max(max_penetration_, deepest.depth);
  const auto n = static_cast<std::int64_t>(contacts_->points.size());
  contact_points_ += n;
  max_contact_points_ = std::max(max_contact_points_, n);
  check_blowup(*robot_, *objects_, *contacts_, deepest, limits_, t);
  objects_out_of_bounds_ += objects_->remove_beyond(config_.world_radius);
  objects_->write_states(*object_states_);
}

void BulletWorld::finish(NodeContext& ctx) {
  ctx.report_metric("steps", steps_);
  ctx.report_metric("contact_points", contact_points_);
  ctx.report_metric("max_contact_points", max_contact_points_);
  ctx.report_metric("max_penetration_m", max_penetration_);
  ctx.report_metric("objects_spawned", objects_spawned_);
  ctx.report_metric("objects_out_of_bounds", objects_out_of_bounds_);
  ctx.report_metric("objects_withdrawn", objects_withdrawn_);
}

}  // namespace somasim::bullet_world
