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

PluginSpec BulletWorld::spec() {
  PluginSpec s("bullet_world",
               "Physics (Bullet, double precision): the robot as a fixed-base btMultiBody with "
               "joint motors and limits, gravity, self-collision (adjacent links filtered), "
               "static/dynamic/kinematic/guided objects and contacts. One fixed step per tick.");
  robot::add_robot_param(s);
  s.add_string("initial_posture_deg")
      .accepts_map_as_text()
      .defaults(std::string(""))
      .describe(
          "initial joint values held by the motors, 'joint: value, ...' in degrees (prismatic: "
          "m); unlisted joints start at 0 clamped into their limits");
  s.add_string("encoder_offsets_deg")
      .accepts_map_as_text()
      .defaults(std::string(""))
      .describe(
          "miscalibrated encoders, 'joint: beta, ...' in degrees: the real joint values are the "
          "encoder readings plus beta (body-schema study). joint_state reports real - beta and "
          "position commands are encoder values (the motors drive real = command + beta); "
          "initial_posture_deg and link_poses are real");
  s.add_string_list("locked_joints")
      .defaults(std::vector<std::string>{})
      .describe(
          "joints fixed at their initial value (names, or 'all'): "
          "folded into rigid bodies, no dynamics and no motor; a command on them stops the run. "
          "With 'all' the robot is static collision geometry (fastest; contacts still reported)");
  s.add_list("gravity")
      .size(3)
      .unit_is("m/s^2")
      .defaults(std::vector<double>{0, 0, -9.81})
      .describe("gravity in the root frame");
  s.add_double("position_gain")
      .unit_is("1/s")
      .defaults(40.0)
      .range(0, 1e4)
      .describe(
          "motor position gain: target joint velocity = position_gain * (q* - q) + v*; a step "
          "settles (2%) in about 4/position_gain");
  s.add_double("velocity_gain")
      .defaults(1.0)
      .range(0, 1)
      .describe("motor velocity gain: weight of the velocity target (1 = track it exactly)");
  s.add_double("max_torque")
      .unit_is("N*m")
      .defaults(20.0)
      .range(0, 1e4)
      .describe("largest motor torque per joint (prismatic joints: N)");
  s.add_int("solver_iterations")
      .defaults(std::int64_t{20})
      .range(1, 1000)
      .describe(
          "iterations of Bullet's constraint solver per step (the solver is most of a step's "
          "cost; below about 15 the motors no longer hold a ball's weight firmly)");
  s.add_string("scene")
      .defaults(std::string(""))
      .describe(
          "optional scene file with objects present from t = 0 (format in "
          "somasim/robot/scene_file.hpp), relative to the experiment file");
  s.add_double("friction")
      .defaults(0.8)
      .range(0, 10)
      .describe("friction coefficient of links and objects");
  s.add_double("rolling_friction")
      .unit_is("m")
      .defaults(0.0005)
      .range(0, 1)
      .describe("rolling and spinning friction of objects (lets balls come to rest)");
  s.add_double("restitution")
      .defaults(0.0)
      .range(0, 1)
      .describe("restitution of links and objects");
  s.add_double("contact_distance")
      .unit_is("m")
      .defaults(0.0005)
      .range(0, 0.1)
      .describe("contact points closer than this (or penetrating) are reported");
  s.add_double("kinematic_contact_stiffness")
      .unit_is("N/m")
      .defaults(1000.0)
      .range(0, 1e7)
      .describe(
          "normal force per metre of penetration reported for a kinematic object touching "
          "immovable robot geometry (locked links, the fixed base), where the solver applies no "
          "force; the object keeps its path");
  s.add_double("guide_max_force")
      .unit_is("N")
      .defaults(5.0)
      .range(0, 1e4)
      .describe(
          "largest force that pulls a guided object along its path (a hand holding it): "
          "against the robot it presses with at most this much");
  s.add_double("guide_bandwidth")
      .unit_is("1/s")
      .defaults(100.0)
      .range(1, 1e4)
      .describe(
          "bandwidth of the critically damped servo that keeps a guided object on its path "
          "(keep bandwidth x step well below 1)");
  s.add_double("guide_contact_stiffness")
      .unit_is("N/m")
      .defaults(1000.0)
      .range(0, 1e7)
      .describe(
          "contact stiffness of guided objects (0: rigid): pressed with F, a guided object sinks "
          "about F / stiffness into what it touches, as a held object into the soft skin "
          "(the same law as kinematic_contact_stiffness)");
  s.add_double("contact_history")
      .unit_is("s")
      .defaults(0.1)
      .range(0, 10)
      .describe(
          "contacts of this recent past are kept in the output's `recent` list, so that "
          "slower nodes (a 50 Hz skin) see brief impacts");
  s.add_double("spawn_tolerance")
      .unit_is("m")
      .defaults(0.001)
      .range(0, 1)
      .describe("an object may start overlapping a robot link by at most this much");
  s.add_double("world_radius")
      .unit_is("m")
      .defaults(10.0)
      .range(0.1, 1e6)
      .describe("dynamic objects farther than this from the root are removed (fell away)");
  s.add_double("max_joint_speed")
      .unit_is("rad/s")
      .defaults(99.0)
      .range(0, 99)
      .describe(
          "blow-up bound: a faster joint stops the run (kept below Bullet's own clamp of joint "
          "speeds at 100 rad/s, which a blown-up joint sits at; hard contacts can briefly "
          "drive a light joint to ~70 rad/s)");
  s.add_double("max_object_speed")
      .unit_is("m/s")
      .defaults(50.0)
      .range(0, 1e6)
      .describe("blow-up bound: a faster object stops the run");
  s.add_double("max_penetration")
      .unit_is("m")
      .defaults(0.02)
      .range(0, 10)
      .describe("blow-up bound: a deeper interpenetration stops the run");
  s.input<JointCommand>("commands",
                        "joint commands (position/velocity per dof; kNone keeps the last target)",
                        /*optional=*/true);
  s.input<ObjectSpawns>("spawns", "objects to add (each id once)", /*optional=*/true);
  s.output<JointState>("joint_state", "joint positions [rad] and velocities [rad/s], dof order");
  s.output<LinkPoses>("link_poses", "pose of every model link in the root frame, link order");
  s.output<ObjectStates>("objects", "state of every object, spawn order (root frame)");
  s.output<Contacts>("contacts",
                     "contact points of the last step: bodies, point (root and link-a frame), "
                     "normal from b to a, normal force [N]");
  return s;
}

void BulletWorld::configure(NodeContext& ctx) {
  model_ = robot::experiment_robot(ctx);
  Eigen::VectorXd q0;
  try {
    q0 = robot::parse_posture_deg(*model_, ctx.param<std::string>("initial_posture_deg"));
  } catch (const InputError& e) {
    ctx.param_error("initial_posture_deg", e.what());
  }
  try {
    encoder_offsets_ =
        robot::parse_joint_offsets(*model_, ctx.param<std::string>("encoder_offsets_deg"));
  } catch (const InputError& e) {
    ctx.param_error("encoder_offsets_deg", e.what());
  }
  miscalibrated_ = !encoder_offsets_.isZero();
  std::vector<bool> locked;
  try {
    locked = parse_locked_joints(ctx.param<std::vector<std::string>>("locked_joints"), *model_);
  } catch (const InputError& e) {
    ctx.param_error("locked_joints", e.what());
  }
  dt_ = ctx.period_s();
  contact_distance_ = ctx.param<double>("contact_distance");
  contact_history_ = ctx.param<double>("contact_history");
  kinematic_stiffness_ = ctx.param<double>("kinematic_contact_stiffness");
  spawn_tolerance_ = ctx.param<double>("spawn_tolerance");
  world_radius_ = ctx.param<double>("world_radius");
  limits_ = {ctx.param<double>("max_joint_speed"), ctx.param<double>("max_object_speed"),
             ctx.param<double>("max_penetration")};
  const auto g = ctx.param<std::vector<double>>("gravity");
  const double friction = ctx.param<double>("friction");
  const double rolling = ctx.param<double>("rolling_friction");
  const double restitution = ctx.param<double>("restitution");

  physics_ = std::make_unique<PhysicsWorld>(Eigen::Vector3d(g[0], g[1], g[2]),
                                            ctx.param<int>("solver_iterations"));
  filter_ = std::make_unique<SelfCollisionFilter>(*model_, locked);
  physics_->set_pair_filter(filter_.get());
  shapes_ = std::make_unique<ShapeStore>();
  try {
    robot_ = std::make_unique<RobotMultiBody>(model_, physics_->world(), *shapes_, q0,
                                              LinkMaterial{friction, 0.0, restitution}, locked);
  } catch (const InputError& e) {  // e.g. a collision mesh that cannot be used
    robot::robot_error(ctx, e.what());
  }
  const MotorGains gains{ctx.param<double>("position_gain"), ctx.param<double>("velocity_gain"),
                         ctx.param<double>("max_torque")};
  motors_ = std::make_unique<JointMotors>(*robot_, physics_->world(), gains, dt_, q0);
  const ObjectGuide guide{ctx.param<double>("guide_max_force"),
                          ctx.param<double>("guide_bandwidth"),
                          ctx.param<double>("guide_contact_stiffness")};
  if (guide.bandwidth * dt_ > 0.5)
    ctx.param_error("guide_bandwidth",
                    fmt::format("{} 1/s at a {} s step makes the guide unstable: keep "
                                "guide_bandwidth x step <= 0.5 (here <= {:g} 1/s)",
                                guide.bandwidth, dt_, 0.5 / dt_));
  objects_ = std::make_unique<ObjectManager>(physics_->world(), *shapes_,
                                             ObjectMaterial{friction, rolling, restitution}, guide);
  physics_->world().updateAabbs();

  if (const std::string scene = ctx.param<std::string>("scene"); !scene.empty()) {
    std::vector<robot::SceneObject> objects;
    try {
      objects = robot::load_scene(ctx.resolve_input_path(scene));
    } catch (const InputError& e) {
      ctx.param_error("scene", e.what());
    }
    for (const robot::SceneObject& so : objects) {
      int i = -1;
      try {
        i = objects_->add(so.spawn, 0.0);
      } catch (const InputError& e) {  // e.g. a mesh that cannot be used
        ctx.param_error(
            "scene", fmt::format("{}: object '{}': {}", so.where.str(), so.spawn.name, e.what()));
      }
      const RobotOverlap overlap =
          deepest_robot_overlap(physics_->world(), *robot_, objects_->body(i));
      if (overlap.link >= 0 && overlap.depth > spawn_tolerance_)
        throw InputError(
            fmt::format("{}: object '{}' starts inside the robot: it overlaps link "
                        "'{}' by {:.1f} mm",
                        so.where.str(), objects_->name(i), model_->link(overlap.link).name,
                        overlap.depth * 1e3));
      ++objects_spawned_;
    }
  }

  joint_state_ = &ctx.output<JointState>("joint_state");
  link_poses_ = &ctx.output<LinkPoses>("link_poses");
  object_states_ = &ctx.output<ObjectStates>("objects");
  contacts_ = &ctx.output<Contacts>("contacts");
  if (ctx.is_wired("commands")) commands_ = &ctx.input<JointCommand>("commands");
  if (ctx.is_wired("spawns")) spawns_ = &ctx.input<ObjectSpawns>("spawns");
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
    if (overlap.link >= 0 && overlap.depth > spawn_tolerance_)
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
  motors_->update_limits();
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
                       contact_distance_, kinematic_stiffness_, *contacts_);
  record_contact_history(*contacts_, t, contact_history_);
  max_penetration_ = std::max(max_penetration_, deepest.depth);
  const auto n = static_cast<std::int64_t>(contacts_->points.size());
  contact_points_ += n;
  max_contact_points_ = std::max(max_contact_points_, n);
  check_blowup(*robot_, *objects_, *contacts_, deepest, limits_, t);
  objects_out_of_bounds_ += objects_->remove_beyond(world_radius_);
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
