#include "object_thrower.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "somasim/diagnostics.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/units.hpp"

#include "skin_link_shapes.hpp"

namespace somasim::plugins {

namespace {
const std::vector<std::string> kShapeNames = {"sphere", "box", "cylinder"};
const std::vector<std::string> kMotionNames = {"approach", "static", "receding"};

// The least clearance [m] of an object's path from the links it is not aimed at: where no path
// keeps path_clearance, the presentation is drawn again with this one.
constexpr double kLeastPathClearance = 0.005;
// How far an object stays from the shapes of its aimed link beside the skin (a hand's thumb and
// fingers beside the palm's skin) until it touches the skin [m]. They move with the skin, so this
// is a contact margin, not room for the arm's motion as path_clearance is.
constexpr double kBesideSkinClearance = 0.002;
// Taxels drawn, and paths tried for each, before a presentation is given up as impossible.
constexpr int kTaxelDraws = 50;
constexpr int kPathAttempts = 100;
// While no presentation can be placed, it is tried again this often [s].
constexpr double kRetryInterval = 0.5;

// Radius of a sphere around the centre that holds the whole object [m].
double bounding_radius(ObjectShape shape, double size, double half_height) {
  switch (shape) {
    case ObjectShape::kBox:
      return std::sqrt(3.0) * size;
    case ObjectShape::kCylinder:
      return std::hypot(size, half_height);
    default:
      return size;
  }
}

}  // namespace

template <class V>
void ObjectThrower::Config::visit(V& v) {
  v.block(robot);
  v.field("parts", parts).doc("skin parts to aim at, in turn");
  v.field("shapes", shapes)
      .doc(
          "space-separated object shapes (sphere, box, cylinder), in turn (with two parts, "
          "'sphere sphere box box' gives each part both)");
  v.field("motions", motions).doc("motions (approach, static, receding), in turn");
  v.field("size", size)
      .unit("m")
      .range(0.001, 0.5)
      .doc("sphere radius / half edge of the cube / cylinder radius");
  v.field("box_facing", box_facing)
      .doc(
          "what of a cube meets the aimed taxel: a face (stimulus radius = half edge) or a "
          "corner (a point contact like a ball's; radius = half diagonal, sqrt(3) x size)");
  v.field("cylinder_half_height", cylinder_half_height)
      .unit("m")
      .range(0.001, 0.5)
      .doc("half height of cylinders (their side faces the taxel)");
  v.field("cylinder_axis", cylinder_axis)
      .doc(
          "how a cylinder's axis lies across the aimed taxel's normal: any (a direction fixed by "
          "the normal alone), across_part (across the skin part's long axis, the direction of "
          "largest spread of its taxels: a cylinder spans a forearm's width, its round side "
          "along the forearm) or along_part");
  v.field("path_clearance", path_clearance)
      .unit("m")
      .range(0.0, 0.2)
      .doc(
          "how far an object's path (the whole object) stays from every robot link but the "
          "aimed one; a taxel no such path reaches is given up for another (unreachable_draws), "
          "and where no taxel can be reached so (a large object beside the hand) the "
          "presentation is drawn again keeping 5 mm (presentations_reduced_clearance). Raise it "
          "where the robot moves toward the object (reaching), so that the arm's own motion "
          "does not bring a neighbouring link (the hand next to a wrist taxel) into the "
          "object's way. The aimed link's own shapes beside the skin (a hand's thumb and "
          "fingers beside the palm's skin) move with the skin: the whole object keeps 2 mm from "
          "them until it touches the skin, along its path and along the part's normal "
          "(paths_met_beside_skin counts the paths given up for them). Where no taxel is "
          "reached with the object held as presented, the taxels are drawn again with the "
          "object turned about the aimed normal by a random angle (presentations_turned)");
  v.field("distance_min", distance_min)
      .unit("m")
      .range(0.0, 5)
      .doc("smallest start distance of approaching and static objects (surface to taxel)");
  v.field("distance_max", distance_max)
      .unit("m")
      .range(0.01, 5)
      .doc("largest start distance; also how far receding objects travel");
  v.field("receding_start_min", receding_start_min)
      .unit("m")
      .range(0.0, 5)
      .doc("smallest start distance of receding objects (surface to taxel)");
  v.field("receding_start_max", receding_start_max)
      .unit("m")
      .range(0.0, 5)
      .doc("largest start distance of receding objects");
  v.field("static_duration", static_duration)
      .unit("s")
      .range(0.01, 1000)
      .doc("how long a static object stays");
  v.field("cone_deg", cone_deg)
      .unit("deg")
      .range(0, 89)
      .doc("start directions within this angle of the aimed taxel's normal");
  v.field("speed_min", speed_min)
      .unit("m/s")
      .range(0.001, 10)
      .doc("smallest speed of approaching and receding objects");
  v.field("speed_max", speed_max).unit("m/s").range(0.001, 10).doc("largest speed");
  v.field("approaches", approaches)
      .range(1, 1000000)
      .doc("objects presented (all motions); the run stops after the last");
  v.field("pause", pause)
      .unit("s")
      .range(0, 100)
      .doc("pause between the removal of an object and the next one");
  v.field("first_after", first_after)
      .unit("s")
      .range(0, 1e6)
      .doc("the first object appears this long after the start (e.g. once the gaze settled)");
  v.field("linger", linger)
      .unit("s")
      .range(0, 10)
      .doc("an approaching object is removed this long after reaching the skin");
  v.field("withdraw_after_skin_contact", withdraw_after_skin_contact)
      .unit("s")
      .range(-1, 100)
      .doc(
          "the object is withdrawn (removed from the world) this long after the skin first "
          "reports a contact during its presentation — a person holding it does not push on "
          "into an arm that came to meet it; needs the 'contacts' input; < 0: it flies its "
          "whole planned path");
  v.field("withdraw_after_robot_contact", withdraw_after_robot_contact)
      .unit("s")
      .range(-1, 100)
      .doc(
          "the object is withdrawn this long after it first touches any robot link, with or "
          "without skin (the world's contacts); needs the 'world_contacts' input; < 0: off");
  v.field("wait_for_clear_path", wait_for_clear_path)
      .unit("s")
      .range(0, 1e6)
      .doc(
          "when no path clear of the robot reaches the part (the posture blocks it), the "
          "presentation is tried again every 0.5 s for this long, then the run stops naming "
          "what was tried (metric presentations_postponed)");
  v.field("object_motion", object_motion)
      .one_of({"guided", "kinematic"})
      .doc(
          "guided: a dynamic body pulled along its path by a bounded force (bullet_world's "
          "guide_max_force), stopped by what it meets, as in a hand; kinematic: moved along "
          "its path whatever it meets (pushes the robot without bound)");
  v.field("mass", mass).unit("kg").range(1e-4, 100).doc("mass of guided objects");
  v.field("view", view)
      .doc(
          "whether the cameras (view_cameras) can see each object coming - all of it in their "
          "images where it appears, then its centre in them and not behind the robot's links "
          "until view_until from the skin, the head as it is when the object appears: report "
          "labels each presentation (its 'sight'; metric presentations_out_of_view), require "
          "presents only objects seen coming (paths_out_of_view counts the paths given up), "
          "ignore does neither; needs link_poses");
  v.field("view_cameras", view_cameras)
      .doc("cameras that must see the object (empty: every camera of the robot)");
  v.field("view_until", view_until)
      .unit("m")
      .range(0, 5)
      .doc("an approaching object must be seen until this far from the end of its path");
  v.field("view_margin", view_margin)
      .unit("px")
      .range(0, 1000)
      .doc("the object's centre stays this far inside the images");
  v.field("position_noise", position_noise)
      .unit("m")
      .range(0, 1)
      .doc("perceived position noise (Gaussian σ per axis)");
  v.field("velocity_noise", velocity_noise)
      .unit("m/s")
      .range(0, 10)
      .doc("perceived velocity noise (Gaussian σ per axis)");
  v.field("vision_link", vision_link)
      .doc(
          "link the cameras are on, for vision through the believed kinematics ('' = the link "
          "of the robot's left_eye camera)");
}

void ObjectThrower::Config::validate(ConfigChecks& checks) const {
  checks.require(!parts.empty(), parts, "expected at least one skin part name");
  checks.require(!shapes.empty(), shapes, "expected at least one shape (sphere, box)");
  for (const auto& s : shapes)
    checks.require(std::find(kShapeNames.begin(), kShapeNames.end(), s) != kShapeNames.end(),
                   shapes,
                   "unknown shape '" + s + "'" + did_you_mean(s, kShapeNames) +
                       "; expected sphere, box or cylinder");
  checks.require(!motions.empty(), motions,
                 "expected at least one motion (approach, static, receding)");
  for (const auto& m : motions)
    checks.require(std::find(kMotionNames.begin(), kMotionNames.end(), m) != kMotionNames.end(),
                   motions,
                   "unknown motion '" + m + "'" + did_you_mean(m, kMotionNames) +
                       "; expected approach, static or receding");
}

template <class V>
void ObjectThrower::Ports::visit(V& v) {
  v.port("taxels", taxels, "skin taxel poses (root frame, true kinematics)");
  v.port("state", state, "true joint values (the true camera pose)");
  v.port("objects", objects, "object states from the world (ground truth)");
  v.port("believed_state", believed_state,
         "believed joint values (believed_kinematics.state): the object is placed "
         "through the believed camera pose; unwired: truth + noise");
  v.port("link_poses", link_poses, "robot link poses: start points are drawn clear of the robot");
  v.port("contacts", contacts,
         "skin contact events (for true_offsets and withdraw_after_skin_contact)");
  v.port("world_contacts", world_contacts,
         "the world's contacts (world.contacts): touches of any robot link by the "
         "current object are counted (metrics robot_contact_*) and can end it "
         "(withdraw_after_robot_contact)");
  v.port("believed_taxels", believed_taxels,
         "taxels posed by the believed kinematics (believed_kinematics.taxels), for "
         "the perceived D of true_offsets; unwired: the true taxels");
  v.port(
      "learner_stimulus", learner_stimulus,
      "the stimulus the PPS learner is fed when it is not this node's (e.g. an object tracker's, "
      "wired delayed): the perceived D of true_offsets then subtracts the radius the learner "
      "perceives (its median over the presentation so far) instead of the contact distance - a "
      "learner's D subtracts the radius it perceives, and a tracker's radius of a cube meeting "
      "the skin with a corner is ~1 cm below that corner's distance from the centre");
  v.port("spawns", spawns, "objects to add to the world");
  v.port("stimulus", stimulus, "the object as the robot perceives it (root frame)");
  v.port("truth", truth, "the object's true centre and velocity (root frame)");
  v.port("presentation", presentation, "the object presented now (motion, aimed taxel)");
  v.port("true_offsets", true_offsets,
         "per taxel 'part/id': mean perceived D − true D over its contact events "
         "[m]; NaN while never touched (needs 'contacts')");
}

PluginSpec ObjectThrower::spec() {
  return make_plugin_spec<Config, Ports>(
      "object_thrower",
      "Presents objects (balls, cubes, cylinders) one at a time at random taxels of skin "
      "parts - approaching, static or receding - and publishes each as the robot "
      "perceives it (ground truth + noise, seen through the believed head/eye "
      "kinematics), and the offset each touched taxel should learn.");
}

void ObjectThrower::read_lists(NodeContext& ctx) {
  std::vector<std::string> known;
  for (const auto& patch : model_->skin_patches()) known.push_back(patch.body_part);
  for (const auto& p : config_.parts)
    if (std::find(known.begin(), known.end(), p) == known.end())
      config_error(ctx, config_, config_.parts,
                   "unknown skin part '" + p + "'" + did_you_mean(p, known) +
                       "; the robot's skin parts: " + join_names(known));

  // Names checked in Config::validate().
  const ObjectShape shapes[] = {ObjectShape::kSphere, ObjectShape::kBox, ObjectShape::kCylinder};
  for (const auto& s : config_.shapes)
    shapes_.push_back(
        shapes[std::find(kShapeNames.begin(), kShapeNames.end(), s) - kShapeNames.begin()]);
  const PresentationMotion motions[] = {PresentationMotion::kApproach, PresentationMotion::kStatic,
                                        PresentationMotion::kReceding};
  for (const auto& m : config_.motions)
    motions_.push_back(
        motions[std::find(kMotionNames.begin(), kMotionNames.end(), m) - kMotionNames.begin()]);
}

void ObjectThrower::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  read_lists(ctx);

  auto& g = geometry_;
  g.size = config_.size;
  cylinder_half_height_ = config_.cylinder_half_height;
  box_corner_ = config_.box_facing == BoxFacing::kCorner;
  g.distance_min = config_.distance_min;
  g.distance_max = config_.distance_max;
  if (g.distance_max < g.distance_min)
    config_error(ctx, config_, config_.distance_max, "must not be less than distance_min");
  g.receding_start_min = config_.receding_start_min;
  g.receding_start_max = config_.receding_start_max;
  if (g.receding_start_max < g.receding_start_min)
    config_error(ctx, config_, config_.receding_start_max,
                 "must not be less than receding_start_min");
  g.static_duration = config_.static_duration;
  g.cone_rad = deg_to_rad(config_.cone_deg);
  g.speed_min = config_.speed_min;
  g.speed_max = config_.speed_max;
  if (g.speed_max < g.speed_min)
    config_error(ctx, config_, config_.speed_max, "must not be less than speed_min");
  g.linger = config_.linger;
  pause_ = config_.pause;
  retry_at_s_ = config_.first_after;
  position_noise_ = config_.position_noise;
  velocity_noise_ = config_.velocity_noise;

  skin_ = &ports_.taxels.get();
  state_ = &ports_.state.get();
  objects_ = &ports_.objects.get();
  if (ports_.believed_state.wired()) {
    believed_state_ = ports_.believed_state.get();
    const std::string name = config_.vision_link;
    int link = -1;
    if (name.empty()) {
      const int camera = model_->find_camera("left_eye");
      if (camera < 0)
        config_error(ctx, config_, config_.vision_link,
                     "robot '" + model_->name() +
                         "' has no 'left_eye' camera; name the link the "
                         "cameras are on");
      link = model_->cameras()[static_cast<std::size_t>(camera)].link;
    } else {
      try {
        link = model_->link_index(name);
      } catch (const InputError& e) {
        config_error(ctx, config_, config_.vision_link, e.what());
      }
    }
    vision_ = std::make_unique<BelievedVision>(model_, link);
  }
  link_poses_ = ports_.link_poses.get();
  contacts_ = ports_.contacts.get();
  if (config_.withdraw_after_skin_contact >= 0 && !contacts_)
    config_error(ctx, config_, config_.withdraw_after_skin_contact,
                 "needs the skin's contact events: wire input 'contacts' (e.g. skin.contacts)");
  configure_view(ctx);
  object_motion_ =
      config_.object_motion == "kinematic" ? ObjectMotion::kKinematic : ObjectMotion::kGuided;
  if (ports_.world_contacts.wired()) {
    robot_contacts_ = std::make_unique<RobotContactLog>(*model_);
    world_contacts_ = ports_.world_contacts.get();
  }
  if (config_.withdraw_after_robot_contact >= 0 && !world_contacts_)
    config_error(ctx, config_, config_.withdraw_after_robot_contact,
                 "needs the world's contacts: wire input 'world_contacts' (e.g. world.contacts)");
  believed_taxels_ = ports_.believed_taxels.get();
  learner_stimulus_ = ports_.learner_stimulus.get();
  if (learner_stimulus_ && !contacts_)
    ctx.node_error(
        "input 'learner_stimulus' is used only for true_offsets, which need the skin's contact "
        "events: wire input 'contacts' (e.g. skin.contacts)");
  spawns_ = &ports_.spawns.get();
  stimulus_ = &ports_.stimulus.get();
  truth_ = &ports_.truth.get();
  presentation_ = &ports_.presentation.get();
  true_offsets_out_ = &ports_.true_offsets.get();
}

void ObjectThrower::configure_view(NodeContext& ctx) {
  if (config_.view == ViewPolicy::kIgnore) return;
  std::vector<std::string> known;
  for (const auto& c : model_->cameras()) known.push_back(c.name);
  std::vector<int> cameras;
  for (const auto& name : config_.view_cameras) {
    const int c = model_->find_camera(name);
    if (c < 0)
      config_error(ctx, config_, config_.view_cameras,
                   "unknown camera '" + name + "'" + did_you_mean(name, known) +
                       "; the robot's cameras: " + join_names(known));
    if (std::find(cameras.begin(), cameras.end(), c) != cameras.end())
      config_error(ctx, config_, config_.view_cameras, "camera '" + name + "' is named twice");
    cameras.push_back(c);
  }
  if (cameras.empty())
    for (int c = 0; c < static_cast<int>(model_->cameras().size()); ++c) cameras.push_back(c);
  const bool can_check = link_poses_ && !cameras.empty();
  if (config_.view == ViewPolicy::kRequire && !can_check)
    config_error(ctx, config_, config_.view,
                 link_poses_ ? "robot '" + model_->name() + "' has no camera"
                             : std::string("needs the robot's link poses: wire "
                                           "input 'link_poses' (world.link_poses)"));
  if (can_check)
    view_ = std::make_unique<PresentationView>(*model_, std::move(cameras), config_.view_until,
                                               config_.view_margin);
}

bool ObjectThrower::launch(NodeContext& ctx) {
  const std::size_t index = static_cast<std::size_t>(launched_);
  // Parts, shapes and motions in turn, each with the presentation index.
  const std::string& part = config_.parts[index % config_.parts.size()];
  const ObjectShape shape = shapes_[index % shapes_.size()];
  const PresentationMotion motion = motions_[index % motions_.size()];
  const SkinPart* sp = nullptr;
  for (const auto& p : skin_->parts)
    if (p.name == part) sp = &p;
  if (!sp || sp->taxel_ids.empty())
    throw RunError("skin part '" + part +
                   "' is not in the 'taxels' input (is the skin node wired?)");
  auto& rng = ctx.rng();
  std::uniform_int_distribution<std::size_t> pick(0, sp->taxel_ids.size() - 1);
  // The distance from the centre to the skin at contact: also the stimulus radius.
  const bool corner = shape == ObjectShape::kBox && box_corner_;
  radius_ = corner ? std::sqrt(3.0) * geometry_.size : geometry_.size;
  PresentationGeometry g = geometry_;
  g.size = radius_;
  // The start clear of the whole robot; the path of the object (its cover of spheres, turned
  // as it will be presented) clear of every link but the aimed one, so that it reaches the
  // skin it is aimed at without meeting another link first. A taxel no such path reaches is
  // given up for another one.
  const double reach = bounding_radius(shape, geometry_.size, cylinder_half_height_);
  const int aimed_link = model_->link_index(sp->link);
  const Eigen::Vector3d long_axis =
      shape == ObjectShape::kCylinder && config_.cylinder_axis != CylinderAxis::kAny
          ? part_long_axis(sp->positions)
          : Eigen::Vector3d::Zero();
  // The aimed link's shapes beside the skin, met before the skin by an object larger than the
  // part aimed near its edge (a thumb standing above the palm).
  const std::vector<robot::Geometry> beside_skin =
      link_poses_ ? shapes_beside_skin(model_->link(aimed_link).collision, sp->positions_link)
                  : std::vector<robot::Geometry>{};
  std::size_t k = 0;
  PresentedBody body;
  std::vector<robot::CoverSphere> cover;
  std::pair<Eigen::Vector3d, Eigen::Vector3d> path;  // of the last path accepted
  std::optional<std::string> unseen;                 // why the last path tried was not seen
  int out_of_view = 0;                               // paths given up as not seen
  double clearance = config_.path_clearance;
  const auto clear = [&](const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
    if (!link_poses_) return true;
    if (!robot::point_clear_of_robot(*model_, link_poses_->poses, start, reach + 0.01) ||
        !robot::object_path_clear_of_robot(*model_, link_poses_->poses, cover, body.rotation, start,
                                           end, clearance, std::span(&aimed_link, 1)))
      return false;
    const std::optional<robot::Geometry> solid = robot::object_geometry(shape, body.size);
    if (!beside_skin.empty() && solid) {
      // The object reaches the skin before the aimed link's other shapes along its path and
      // along the part's normal (the way a reaching part moves toward it).
      const Eigen::Isometry3d& link_pose = link_poses_->poses[static_cast<std::size_t>(aimed_link)];
      const Eigen::Vector3d normal_start = end + sp->normals[k].normalized() * (end - start).norm();
      if (!robot::object_path_clear_of_shapes(*solid, body.rotation, start, end, beside_skin,
                                              link_pose, kBesideSkinClearance) ||
          (motion == PresentationMotion::kApproach &&
           !robot::object_path_clear_of_shapes(*solid, body.rotation, normal_start, end,
                                               beside_skin, link_pose, kBesideSkinClearance))) {
        ++paths_met_beside_skin_;
        return false;
      }
    }
    if (config_.view == ViewPolicy::kRequire) {
      unseen = view_->unseen(link_poses_->poses, motion, start, end, reach);
      if (unseen) {
        ++out_of_view;
        return false;
      }
    }
    path = {start, end};
    return true;
  };
  std::optional<PlannedObject> planned;
  bool reduced = false;  // placed with the least clearance, the preferred one kept by no path
  bool turned = false;   // turned about the aimed normal, no path clear as it is presented
  std::uniform_real_distribution<double> turn(0.0, std::numbers::pi);
  for (int draw = 0; !planned; ++draw) {
    if (draw == kTaxelDraws && clearance > kLeastPathClearance) {
      // No taxel is reached keeping path_clearance: draw them again keeping the least one.
      clearance = kLeastPathClearance;
      reduced = true;
      draw = 0;
    }
    if (draw == kTaxelDraws && !turned && shape != ObjectShape::kSphere) {
      // No taxel is reached with the object held as presented (a cylinder wider than the palm,
      // across the thumb): draw them again, each with the object turned about the aimed normal
      // by a random angle, as a person would turn it to bring it to the skin.
      turned = true;
      draw = 0;
    }
    if (draw == kTaxelDraws) {
      unplaced_ = fmt::format(
          "no path clear of the robot for a {} (motion '{}') aimed at '{}': {} taxels drawn, {} "
          "paths each (start {}-{} m from the skin within {:.0f} deg of its normal, the object "
          "{} clear of the other links{}{}{}); raise 'distance_min', lower 'cone_deg' or 'size', "
          "or change the posture",
          shape_name(shape), motion_name(motion), part, kTaxelDraws, kPathAttempts,
          motion == PresentationMotion::kReceding ? g.receding_start_min : g.distance_min,
          motion == PresentationMotion::kReceding ? g.receding_start_max : g.distance_max,
          rad_to_deg(g.cone_rad),
          reduced ? fmt::format("{:.3f} m, then {:.3f} m", config_.path_clearance, clearance)
                  : fmt::format("{:.3f} m", clearance),
          beside_skin.empty()
              ? std::string()
              : fmt::format(" and {:.3f} m of its own link's shapes beside the skin until it "
                            "touches the skin",
                            kBesideSkinClearance),
          turned ? std::string(", as presented and then turned about the normal") : std::string(),
          out_of_view == 0
              ? std::string()
              : fmt::format(", seen coming by the cameras (view: require): {} clear paths were "
                            "not, the last {}",
                            out_of_view, *unseen));
      paths_out_of_view_ += out_of_view;
      return false;
    }
    if (draw > 0) ++unreachable_draws_[part];
    k = pick(rng);
    body = presented_body(shape, corner, sp->normals[k].normalized(), geometry_.size,
                          cylinder_half_height_, config_.cylinder_axis, long_axis);
    if (turned)
      body.rotation = Eigen::AngleAxisd(turn(rng), sp->normals[k].normalized()).toRotationMatrix() *
                      body.rotation;
    cover = robot::sphere_cover(shape, body.size);
    planned = plan_presentation(motion, sp->positions[k], sp->normals[k].normalized(), g, rng,
                                clear, kPathAttempts);
  }
  const PlannedObject& plan = *planned;
  paths_out_of_view_ += out_of_view;
  if (reduced) ++reduced_clearance_;
  if (turned) ++turned_about_normal_;
  PresentationSight sight = PresentationSight::kNotChecked;
  if (view_ && link_poses_)
    sight = view_->unseen(link_poses_->poses, motion, path.first, path.second, reach)
                ? PresentationSight::kOutOfView
                : PresentationSight::kInView;
  if (sight == PresentationSight::kOutOfView) ++per_part_out_of_view_[part];

  ObjectSpawn spawn;
  spawn.id = next_spawn_id_++;
  spawn.name = "pps_object_" + std::to_string(spawn.id);
  spawn.shape = shape;
  spawn.motion = object_motion_;
  spawn.mass = config_.mass;
  spawn.pose = Eigen::Isometry3d::Identity();
  spawn.pose.linear() = body.rotation;
  spawn.size = body.size;
  spawn.pose.translation() = plan.start;
  spawn.linear_velocity = plan.velocity;
  spawn.remove_after_s = plan.lifetime;
  spawns_->recent.push_back(spawn);
  while (spawns_->recent.size() > 8) spawns_->recent.erase(spawns_->recent.begin());

  ++launched_;
  Presentation& p = *presentation_;
  p.id = static_cast<std::uint64_t>(launched_);
  p.active = true;
  p.motion = motion;
  p.object = spawn.name;
  p.body_part = part;
  p.taxel_id = sp->taxel_ids[k];
  p.aimed_point = sp->positions[k];
  p.start_time_s = ctx.time_s();
  p.speed = plan.speed;
  p.sight = sight;
  lifetime_ = plan.lifetime;
  withdraw_at_s_ = std::numeric_limits<double>::infinity();
  spawns_->withdraw.clear();
  seen_.reset();
  learner_radii_.clear();
  ++per_part_presentations_[part];
  ++per_motion_[motion_name(motion)];
  return true;
}

void ObjectThrower::perceive(NodeContext& ctx) {
  *truth_ = pps::Stimulus{};
  *stimulus_ = pps::Stimulus{};
  if (!presentation_->active) return;
  int obj = -1;
  for (std::size_t i = 0; i < objects_->names.size(); ++i)
    if (objects_->names[i] == presentation_->object) obj = static_cast<int>(i);
  const auto at = static_cast<std::size_t>(obj);
  if (obj < 0 || at >= objects_->present.size() || !objects_->present[at] ||
      at >= objects_->poses.size())
    return;
  truth_->present = true;
  truth_->position = objects_->poses[at].translation();
  truth_->velocity =
      at < objects_->linear_velocity.size() ? objects_->linear_velocity[at] : Eigen::Vector3d{};
  truth_->radius = radius_;

  Seen seen;
  seen.time_s = ctx.time_s();
  seen.position = truth_->position;
  seen.velocity = truth_->velocity;
  if (vision_) seen.to_perceived = vision_->update(state_->position, believed_state_->position);
  seen_ = seen;

  auto& rng = ctx.rng();
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d p = truth_->position, v = truth_->velocity;
  if (position_noise_ > 0)
    for (int i = 0; i < 3; ++i) p[i] += position_noise_ * gauss(rng);
  if (velocity_noise_ > 0)
    for (int i = 0; i < 3; ++i) v[i] += velocity_noise_ * gauss(rng);
  stimulus_->present = true;
  stimulus_->position = seen.to_perceived * p;
  stimulus_->velocity = seen.to_perceived.linear() * v;  // a direction: rotation only
  stimulus_->radius = radius_;
}

void ObjectThrower::learn_true_offsets() {
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    ++per_part_events_[e.body_part];
    // Only contacts while the current object is in the world (seen at least once).
    if (!seen_ || e.time_s < presentation_->start_time_s ||
        e.time_s > presentation_->start_time_s + lifetime_ + 1e-9)
      continue;
    // The object moves at a constant velocity: its centre at the event, noise-free.
    pps::Stimulus truth;
    truth.position = seen_->position + (e.time_s - seen_->time_s) * seen_->velocity;
    truth.velocity = seen_->velocity;
    truth.radius = radius_;
    pps::Stimulus perceived = truth;
    if (learner_stimulus_) {
      if (learner_radii_.empty()) {
        ++true_offset_events_unseen_;  // the learner never saw it: its D has no radius
        continue;
      }
      perceived.radius = median_learner_radius();
    }
    perceived.position = seen_->to_perceived * truth.position;
    perceived.velocity = seen_->to_perceived.linear() * truth.velocity;
    true_offsets_.add_event(e, *skin_, believed_taxels_ ? *believed_taxels_ : *skin_, perceived,
                            truth, pps::kOffsetClearance);
  }
}

double ObjectThrower::median_learner_radius() const {
  std::vector<double> radii = learner_radii_;
  const auto mid = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
  std::nth_element(radii.begin(), mid, radii.end());
  return *mid;
}

void ObjectThrower::withdraw_when_felt() {
  const Presentation& p = *presentation_;
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_felt_event_id_) continue;
    last_felt_event_id_ = e.id;
    if (p.active && e.time_s >= p.start_time_s)
      withdraw_at(e.time_s + config_.withdraw_after_skin_contact);
  }
}

void ObjectThrower::withdraw_at(double time_s) {
  withdraw_at_s_ = std::min(withdraw_at_s_, time_s);
}

void ObjectThrower::watch_robot_contacts(NodeContext& ctx) {
  const Presentation& p = *presentation_;
  if (!p.active) return;
  const std::optional<double> first =
      robot_contacts_->add(*world_contacts_, *objects_, p.object, p.id);
  for (const int link : robot_contacts_->newly_touched())
    ctx.log().debug("presentation {} ({} aimed at '{}'): touches link '{}' (seen at t = {:.3f} s)",
                    p.id, p.object, p.body_part, model_->link(link).name, ctx.time_s());
  if (first && config_.withdraw_after_robot_contact >= 0)
    withdraw_at(*first + config_.withdraw_after_robot_contact);
}

void ObjectThrower::withdraw_if_due(double now) {
  const Presentation& p = *presentation_;
  if (p.active && now >= withdraw_at_s_ - 1e-9 && spawns_->withdraw.empty()) {
    spawns_->withdraw.push_back(p.object);
    ++withdrawn_;
  }
}

void ObjectThrower::try_launch(NodeContext& ctx, double now) {
  if (launch(ctx)) {
    waiting_since_s_.reset();
    return;
  }
  // No clear path in this posture (e.g. an arm that has just avoided): wait for the robot to
  // move, as the experimenter would, then give up.
  if (!waiting_since_s_) waiting_since_s_ = now;
  ++postponed_;
  if (now - *waiting_since_s_ >= config_.wait_for_clear_path - 1e-9)
    throw RunError(unplaced_ +
                   fmt::format(" (waited {:g} s for a clear path)", now - *waiting_since_s_));
  retry_at_s_ = now + kRetryInterval;
}

void ObjectThrower::step(NodeContext& ctx) {
  const double now = ctx.time_s();
  Presentation& p = *presentation_;
  if (p.active && now - p.start_time_s >= lifetime_ - 1e-9) p.active = false;
  const bool between = launched_ > 0 && now - p.start_time_s < lifetime_ + pause_ - 1e-9;
  const bool done = !p.active && !between && launched_ >= config_.approaches;
  if (!p.active && !between && !done && now >= retry_at_s_ - 1e-9) try_launch(ctx, now);
  if (config_.withdraw_after_skin_contact >= 0) withdraw_when_felt();
  if (world_contacts_) watch_robot_contacts(ctx);
  withdraw_if_due(now);
  perceive(ctx);
  if (learner_stimulus_ && p.active && learner_stimulus_->present)
    learner_radii_.push_back(learner_stimulus_->radius);
  true_offsets_.sync_layout(*skin_);
  if (contacts_) learn_true_offsets();
  true_offsets_.write(*true_offsets_out_);
  ctx.report_progress(launched_, config_.approaches, "objects presented");
  if (done) ctx.request_stop(std::to_string(launched_) + " objects presented");
}

void ObjectThrower::finish(NodeContext& ctx) {
  ctx.report_metric("objects_presented", launched_);
  if (link_poses_) ctx.report_metric("presentations_postponed", postponed_);
  if (link_poses_ && config_.path_clearance > kLeastPathClearance)
    ctx.report_metric("presentations_reduced_clearance", reduced_clearance_);
  if (link_poses_) ctx.report_metric("paths_met_beside_skin", paths_met_beside_skin_);
  if (link_poses_) ctx.report_metric("presentations_turned", turned_about_normal_);
  if (config_.withdraw_after_skin_contact >= 0 || config_.withdraw_after_robot_contact >= 0)
    ctx.report_metric("objects_withdrawn", withdrawn_);
  if (robot_contacts_) robot_contacts_->report(ctx);
  if (view_) {
    int out_of_view = 0;
    for (const auto& [part, n] : per_part_out_of_view_) out_of_view += n;
    ctx.report_metric("presentations_out_of_view", out_of_view);
    if (config_.view == ViewPolicy::kRequire)
      ctx.report_metric("paths_out_of_view", paths_out_of_view_);
  }
  if (learner_stimulus_)
    ctx.report_metric("true_offset_events_unseen_by_learner", true_offset_events_unseen_);
  nlohmann::json per_motion = nlohmann::json::object();
  for (const auto& [motion, n] : per_motion_) per_motion[motion] = n;
  ctx.report_metric("presented_per_motion", per_motion);
  nlohmann::json per_part = nlohmann::json::object();
  const auto means = true_offsets_.part_means();
  for (const auto& [part, n] : per_part_presentations_) {
    per_part[part] = {{"presentations", n}};
    // Taxels drawn but given up: no path to them clear of the other links.
    if (link_poses_) per_part[part]["unreachable_draws"] = unreachable_draws_[part];
    if (contacts_) per_part[part]["contact_events"] = per_part_events_[part];
    if (view_) per_part[part]["out_of_view"] = per_part_out_of_view_[part];
    if (const auto it = means.find(part); it != means.end()) {
      per_part[part]["true_offset_mean_m"] = it->second.first;
      per_part[part]["taxels_touched"] = it->second.second;
    }
  }
  ctx.report_metric("presented_per_part", per_part);
}

}  // namespace somasim::plugins
