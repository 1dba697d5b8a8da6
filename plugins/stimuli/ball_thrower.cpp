#include "ball_thrower.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "somasim/diagnostics.hpp"
#include "somasim/random_directions.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

PluginSpec BallThrower::spec() {
  PluginSpec s("ball_thrower",
               "Throws balls at skin parts one at a time and checks against the physics ground "
               "truth that a ball touching a part yields a skin contact event on that part.");
  robot::add_robot_param(s);
  s.add_string_list("parts")
      .defaults(std::vector<std::string>{"left_forearm", "right_palm"})
      .describe("skin parts to aim at, in turn");
  s.add_int("throws")
      .defaults(std::int64_t{40})
      .range(1, 1000000)
      .describe("balls thrown; the run stops after the last");
  s.add_double("distance")
      .unit_is("m")
      .defaults(0.25)
      .range(0.05, 5)
      .describe("start distance from the aimed taxel");
  s.add_double("cone_deg")
      .unit_is("deg")
      .defaults(40.0)
      .range(0, 89)
      .describe("start directions within this angle of the taxel normal");
  s.add_double("flight_time")
      .unit_is("s")
      .defaults(0.35)
      .range(0.05, 10)
      .describe("time to reach the taxel (ballistic)");
  s.add_double("ball_lifetime")
      .unit_is("s")
      .defaults(1.0)
      .range(0.1, 100)
      .describe("a ball is removed this long after its launch");
  s.add_double("ball_radius").unit_is("m").defaults(0.02).range(0.001, 0.5).describe("ball radius");
  s.add_double("ball_mass").unit_is("kg").defaults(0.05).range(1e-4, 100).describe("ball mass");
  s.add_double("gravity").unit_is("m/s^2").defaults(-9.81).range(-100, 100).describe(
      "gravity along the root z axis (must match the world)");
  s.add_double("skin_margin")
      .unit_is("m")
      .defaults(0.01)
      .range(0, 1)
      .describe(
          "a contact counts as on the part's skin within this distance of one of its (virtual) "
          "taxels");
  s.add_double("event_window")
      .unit_is("s")
      .defaults(0.2)
      .range(0, 10)
      .describe("a skin event this close to the first physical touch counts");
  s.input<SkinTaxels>("taxels", "skin taxel poses (root frame)");
  s.input<LinkPoses>("link_poses", "robot link poses (start points clear of the robot)");
  s.input<ObjectStates>("objects", "object states from the world");
  s.input<Contacts>("contacts", "physical contacts from the world (ground truth)");
  s.input<ContactEvents>("skin_events", "contact events from the skin");
  s.output<ObjectSpawns>("spawns", "balls to add to the world");
  return s;
}

void BallThrower::configure(NodeContext& ctx) {
  model_ = robot::experiment_robot(ctx);
  parts_ = ctx.param<std::vector<std::string>>("parts");
  if (parts_.empty()) ctx.param_error("parts", "expected at least one skin part name");
  std::vector<std::string> known;
  for (const auto& patch : model_->skin_patches()) {
    known.push_back(patch.body_part);
  }
  for (const auto& p : parts_)
    if (std::find(known.begin(), known.end(), p) == known.end())
      ctx.param_error("parts", "unknown skin part '" + p + "'" + did_you_mean(p, known) +
                                   "; the robot's skin parts: " + join_names(known));
  throws_ = ctx.param<int>("throws");
  distance_ = ctx.param<double>("distance");
  cone_rad_ = deg_to_rad(ctx.param<double>("cone_deg"));
  flight_time_ = ctx.param<double>("flight_time");
  lifetime_ = ctx.param<double>("ball_lifetime");
  radius_ = ctx.param<double>("ball_radius");
  mass_ = ctx.param<double>("ball_mass");
  gravity_ = ctx.param<double>("gravity");
  event_window_ = ctx.param<double>("event_window");
  skin_margin_ = ctx.param<double>("skin_margin");
  skin_ = &ctx.input<SkinTaxels>("taxels");
  link_poses_ = &ctx.input<LinkPoses>("link_poses");
  objects_ = &ctx.input<ObjectStates>("objects");
  contacts_ = &ctx.input<Contacts>("contacts");
  events_ = &ctx.input<ContactEvents>("skin_events");
  spawns_ = &ctx.output<ObjectSpawns>("spawns");
}

void BallThrower::launch(NodeContext& ctx) {
  const std::string& part = parts_[static_cast<std::size_t>(thrown_) % parts_.size()];
  const SkinPart* sp = nullptr;
  for (const auto& p : skin_->parts)
    if (p.name == part) sp = &p;
  if (!sp || sp->taxel_ids.empty())
    throw RunError("skin part '" + part +
                   "' is not in the 'taxels' input (is the skin node wired?)");
  std::uniform_int_distribution<std::size_t> pick(0, sp->taxel_ids.size() - 1);
  const std::size_t k = pick(ctx.rng());
  const Eigen::Vector3d n = sp->normals[k].normalized();
  // Aim the ball's centre one radius above the taxel, start within the cone around the normal.
  const Eigen::Vector3d target = sp->positions[k] + radius_ * n;
  Eigen::Vector3d start;
  for (int attempt = 0;; ++attempt) {
    start = target + distance_ * sample_direction_in_cone(n, cone_rad_, ctx.rng());
    if (robot::point_clear_of_robot(*model_, link_poses_->poses, start, radius_ + 0.01)) break;
    if (attempt == 100)
      throw RunError("no start point clear of the robot for a ball aimed at '" + part +
                     "' (lower 'distance' or 'cone_deg')");
  }
  const Eigen::Vector3d g(0, 0, gravity_);
  const double t = flight_time_;
  ObjectSpawn spawn;
  spawn.id = next_spawn_id_++;
  spawn.name = "ball_" + std::to_string(spawn.id);
  spawn.shape = ObjectShape::kSphere;
  spawn.size = Eigen::Vector3d(radius_, 0, 0);
  spawn.motion = ObjectMotion::kDynamic;
  spawn.mass = mass_;
  spawn.pose = Eigen::Isometry3d::Identity();
  spawn.pose.translation() = start;
  spawn.linear_velocity = (target - start - 0.5 * g * t * t) / t;
  spawn.remove_after_s = lifetime_;
  spawns_->recent.push_back(spawn);
  while (spawns_->recent.size() > 8) spawns_->recent.erase(spawns_->recent.begin());
  current_ = Throw{};
  current_.name = spawn.name;
  current_.part = part;
  current_.part_link = model_->link_index(sp->link);
  current_.t_spawn = ctx.time_s();
  active_ = true;
  ++thrown_;
  ++per_part_thrown_[part];
}

void BallThrower::observe() {
  int ball = -1;
  for (std::size_t i = 0; i < objects_->names.size(); ++i)
    if (objects_->names[i] == current_.name) ball = static_cast<int>(i);
  // Every contact since the last step (the world keeps a short history), not just the last one.
  const bool use_history = !contacts_->recent.empty();
  const std::vector<Contact>& points = use_history ? contacts_->recent : contacts_->points;
  double newest = last_contact_time_;
  if (ball >= 0)
    for (const auto& c : points) {
      if (use_history && c.time_s <= last_contact_time_) continue;
      newest = std::max(newest, c.time_s);
      const int link = c.object_a == ball ? c.link_b : (c.object_b == ball ? c.link_a : -1);
      // A touch presses: points within the contact distance but without force are near misses.
      if (link < 0 || !(c.normal_force > 0.0)) continue;
      if (current_.first_touch < 0) current_.first_touch = c.time_s;
      for (const auto& part : skin_->parts)
        if (model_->link_index(part.link) == link && near_skin(part.name, c.point))
          current_.touched_skin = true;
      if (link == current_.part_link) {
        current_.touched_part = true;
        current_.max_force = std::max(current_.max_force, c.normal_force);
        if (near_skin(current_.part, c.point)) current_.touched_part_skin = true;
      }
    }
  last_contact_time_ = newest;
  for (const auto& e : events_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    if (e.time_s + 1e-9 < current_.t_spawn) continue;
    if (e.body_part == current_.part)
      current_.event_on_part = true;
    else
      ++wrong_part_events_;
  }
}

bool BallThrower::near_skin(const std::string& part, const Eigen::Vector3d& point) const {
  for (const auto& p : skin_->parts)
    if (p.name == part)
      for (const auto& x : p.positions)
        if ((x - point).norm() <= skin_margin_) return true;
  return false;
}

void BallThrower::close_throw(NodeContext& ctx) {
  active_ = false;
  ctx.log().debug(
      "{} at {}: first touch {:.3f} s, part link {}, part skin {}, event {}, max force {:.3f} N",
      current_.name, current_.part, current_.first_touch, current_.touched_part,
      current_.touched_part_skin, current_.event_on_part, current_.max_force);
  if (current_.touched_skin) ++hit_skin_;
  if (current_.touched_part) ++touched_expected_link_;
  if (current_.touched_part_skin) {
    ++touched_expected_;
    if (current_.event_on_part) {
      ++hits_on_expected_;
      ++per_part_hits_[current_.part];
    }
  }
}

void BallThrower::step(NodeContext& ctx) {
  const double now = ctx.time_s();
  if (active_) {
    observe();
    // Wait for the world to remove the ball (plus the event window) before the next throw.
    if (now - current_.t_spawn < lifetime_ + event_window_) return;
    close_throw(ctx);
  }
  if (thrown_ >= throws_) {
    ctx.request_stop(std::to_string(thrown_) + " balls thrown");
    return;
  }
  launch(ctx);
}

void BallThrower::finish(NodeContext& ctx) {
  if (active_) close_throw(ctx);
  ctx.report_metric("balls_thrown", thrown_);
  ctx.report_metric("balls_hit_skin", hit_skin_);
  ctx.report_metric("balls_touched_expected_link", touched_expected_link_);
  ctx.report_metric("balls_touched_expected_part", touched_expected_);
  ctx.report_metric("hits_on_expected_part", hits_on_expected_);
  ctx.report_metric("hits_without_event", touched_expected_ - hits_on_expected_);
  ctx.report_metric("events_on_other_parts", wrong_part_events_);
  nlohmann::json per_part = nlohmann::json::object();
  for (const auto& [part, n] : per_part_thrown_)
    per_part[part] = {{"thrown", n}, {"hits_with_event", per_part_hits_[part]}};
  ctx.report_metric("per_part", per_part);
}

}  // namespace somasim::plugins
