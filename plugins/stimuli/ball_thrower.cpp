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

template <class V>
void BallThrower::Config::visit(V& v) {
  v.block(robot);
  v.field("parts", parts).doc("skin parts to aim at, in turn");
  v.field("throws", throws).range(1, 1000000).doc("balls thrown; the run stops after the last");
  v.field("distance", distance).unit("m").range(0.05, 5).doc("start distance from the aimed taxel");
  v.field("cone_deg", cone_deg)
      .unit("deg")
      .range(0, 89)
      .doc("start directions within this angle of the taxel normal");
  v.field("flight_time", flight_time)
      .unit("s")
      .range(0.05, 10)
      .doc("time to reach the taxel (ballistic)");
  v.field("ball_lifetime", ball_lifetime)
      .unit("s")
      .range(0.1, 100)
      .doc("a ball is removed this long after its launch");
  v.field("ball_radius", ball_radius).unit("m").range(0.001, 0.5).doc("ball radius");
  v.field("ball_mass", ball_mass).unit("kg").range(1e-4, 100).doc("ball mass");
  v.field("gravity", gravity)
      .unit("m/s^2")
      .range(-100, 100)
      .doc("gravity along the root z axis (must match the world)");
  v.field("skin_margin", skin_margin)
      .unit("m")
      .range(0, 1)
      .doc(
          "a contact counts as on the part's skin within this distance of one of its (virtual) "
          "taxels");
  v.field("event_window", event_window)
      .unit("s")
      .range(0, 10)
      .doc("a skin event this close to the first physical touch counts");
}

void BallThrower::Config::validate(ConfigChecks& checks) const {
  checks.require(!parts.empty(), parts, "expected at least one skin part name");
}

template <class V>
void BallThrower::Ports::visit(V& v) {
  v.port("taxels", taxels, "skin taxel poses (root frame)");
  v.port("link_poses", link_poses, "robot link poses (start points clear of the robot)");
  v.port("objects", objects, "object states from the world");
  v.port("contacts", contacts, "physical contacts from the world (ground truth)");
  v.port("skin_events", skin_events, "contact events from the skin");
  v.port("spawns", spawns, "balls to add to the world");
}

PluginSpec BallThrower::spec() {
  return make_plugin_spec<Config, Ports>(
      "ball_thrower",
      "Throws balls at skin parts one at a time and checks against the physics ground "
      "truth that a ball touching a part yields a skin contact event on that part.");
}

void BallThrower::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  std::vector<std::string> known;
  for (const auto& patch : model_->skin_patches()) {
    known.push_back(patch.body_part);
  }
  for (const auto& p : config_.parts)
    if (std::find(known.begin(), known.end(), p) == known.end())
      config_error(ctx, config_, config_.parts,
                   "unknown skin part '" + p + "'" + did_you_mean(p, known) +
                       "; the robot's skin parts: " + join_names(known));
  distance_ = config_.distance;
  cone_rad_ = deg_to_rad(config_.cone_deg);
  flight_time_ = config_.flight_time;
  lifetime_ = config_.ball_lifetime;
  radius_ = config_.ball_radius;
  mass_ = config_.ball_mass;
  gravity_ = config_.gravity;
  event_window_ = config_.event_window;
  skin_margin_ = config_.skin_margin;
  skin_ = &ports_.taxels.get();
  link_poses_ = &ports_.link_poses.get();
  objects_ = &ports_.objects.get();
  contacts_ = &ports_.contacts.get();
  events_ = &ports_.skin_events.get();
  spawns_ = &ports_.spawns.get();
}

void BallThrower::launch(NodeContext& ctx) {
  const std::string& part = config_.parts[static_cast<std::size_t>(thrown_) % config_.parts.size()];
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
  ctx.report_progress(thrown_, config_.throws, "balls thrown");
  if (thrown_ >= config_.throws) {
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
