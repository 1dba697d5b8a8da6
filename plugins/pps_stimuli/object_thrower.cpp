#include "object_thrower.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "somasim/diagnostics.hpp"
#include "somasim/random_directions.hpp"
#include "somasim/robot/clearance.hpp"
#include "somasim/robot/robot_cache.hpp"

namespace somasim::plugins {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\n") - b + 1);
}

}  // namespace

PluginSpec ObjectThrower::spec() {
  PluginSpec s("object_thrower",
               "Moves objects (balls, cubes) one at a time toward random taxels of skin parts and "
               "publishes each as the robot perceives it: ground truth + noise, expressed through "
               "the robot's believed kinematics (true joint values + injected offsets).");
  s.add_string("robot").describe("robot description file (skin parts, kinematics)");
  s.add_string("parts")
      .defaults(std::string("left_forearm right_palm"))
      .describe("space-separated skin parts to aim at, in turn");
  s.add_string("shapes")
      .defaults(std::string("sphere box"))
      .describe("space-separated object shapes (sphere, box), in turn");
  s.add_double("size")
      .unit_is("m")
      .defaults(0.025)
      .range(0.001, 0.5)
      .describe("sphere radius / half edge of the cube");
  s.add_double("distance_min")
      .unit_is("m")
      .defaults(0.20)
      .range(0.01, 5)
      .describe("smallest start distance (object surface to the aimed taxel)");
  s.add_double("distance_max")
      .unit_is("m")
      .defaults(0.30)
      .range(0.01, 5)
      .describe("largest start distance");
  s.add_double("cone").unit_is("deg").defaults(45.0).range(0, 89).describe(
      "start directions within this angle of the aimed taxel's normal");
  s.add_double("speed_min")
      .unit_is("m/s")
      .defaults(0.05)
      .range(0.001, 10)
      .describe("smallest approach speed");
  s.add_double("speed_max")
      .unit_is("m/s")
      .defaults(0.15)
      .range(0.001, 10)
      .describe("largest approach speed");
  s.add_int("approaches")
      .defaults(std::int64_t{20})
      .range(1, 1000000)
      .describe("objects thrown; the run stops after the last");
  s.add_double("pause").unit_is("s").defaults(1.0).range(0, 100).describe(
      "pause between the removal of an object and the next approach");
  s.add_double("linger").unit_is("s").defaults(0.1).range(0, 10).describe(
      "an object is removed this long after reaching the skin");
  s.add_double("position_noise")
      .unit_is("m")
      .defaults(0.0)
      .range(0, 1)
      .describe("perceived position noise (Gaussian σ per axis)");
  s.add_double("velocity_noise")
      .unit_is("m/s")
      .defaults(0.0)
      .range(0, 10)
      .describe("perceived velocity noise (Gaussian σ per axis)");
  s.add_string("joint_offsets_deg")
      .defaults(std::string(""))
      .describe(
          "believed-kinematics error, 'joint: value, ...' [deg] (prismatic: [m]) added to the "
          "true joint values");
  s.input<SkinTaxels>("taxels", "skin taxel poses (root frame, true kinematics)");
  s.input<JointState>("state", "true joint values (for the believed kinematics)");
  s.input<ObjectStates>("objects", "object states from the world (ground truth)");
  s.input<LinkPoses>("link_poses", "robot link poses: start points are drawn clear of the robot",
                     /*optional=*/true);
  s.output<ObjectSpawns>("spawns", "objects to add to the world");
  s.output<Stimulus>("stimulus", "the object as the robot perceives it (root frame)");
  s.output<Stimulus>("truth", "the object's true centre and velocity (root frame)");
  return s;
}

void ObjectThrower::configure(NodeContext& ctx) {
  model_ = robot::shared_robot_model(ctx.resolve_input_path(ctx.param<std::string>("robot")));
  true_data_ = std::make_unique<robot::RobotData>(*model_);
  believed_data_ = std::make_unique<robot::RobotData>(*model_);

  std::istringstream in(ctx.param<std::string>("parts"));
  for (std::string p; in >> p;) parts_.push_back(p);
  if (parts_.empty()) ctx.param_error("parts", "expected at least one skin part name");
  std::vector<std::string> known;
  for (const auto& patch : model_->skin_patches()) known.push_back(patch.body_part);
  for (const auto& p : parts_)
    if (std::find(known.begin(), known.end(), p) == known.end())
      ctx.param_error("parts", "unknown skin part '" + p + "'" + did_you_mean(p, known) +
                                   "; the robot's skin parts: " + join_names(known));

  std::istringstream shapes(ctx.param<std::string>("shapes"));
  for (std::string s; shapes >> s;) {
    if (s == "sphere")
      shapes_.push_back(ObjectShape::kSphere);
    else if (s == "box")
      shapes_.push_back(ObjectShape::kBox);
    else
      ctx.param_error("shapes", "unknown shape '" + s + "'" + did_you_mean(s, {"sphere", "box"}) +
                                    "; expected sphere or box");
  }
  if (shapes_.empty()) ctx.param_error("shapes", "expected at least one shape (sphere, box)");

  size_ = ctx.param<double>("size");
  distance_min_ = ctx.param<double>("distance_min");
  distance_max_ = ctx.param<double>("distance_max");
  if (distance_max_ < distance_min_)
    ctx.param_error("distance_max", "must not be less than distance_min");
  cone_rad_ = ctx.param<double>("cone") * M_PI / 180.0;
  speed_min_ = ctx.param<double>("speed_min");
  speed_max_ = ctx.param<double>("speed_max");
  if (speed_max_ < speed_min_) ctx.param_error("speed_max", "must not be less than speed_min");
  approaches_ = ctx.param<int>("approaches");
  pause_ = ctx.param<double>("pause");
  linger_ = ctx.param<double>("linger");
  position_noise_ = ctx.param<double>("position_noise");
  velocity_noise_ = ctx.param<double>("velocity_noise");

  // "joint: value, ..." → per-dof offsets [rad] (prismatic [m]).
  offsets_ = Eigen::VectorXd::Zero(model_->num_dofs());
  std::vector<std::string> joints;
  for (int d = 0; d < model_->num_dofs(); ++d)
    joints.push_back(model_->joint(model_->dof_joint(d)).name);
  std::istringstream entries(ctx.param<std::string>("joint_offsets_deg"));
  for (std::string entry; std::getline(entries, entry, ',');) {
    entry = trim(entry);
    if (entry.empty()) continue;
    const auto colon = entry.find(':');
    if (colon == std::string::npos)
      ctx.param_error("joint_offsets_deg",
                      "expected 'joint: value', got '" + entry + "' (entries separated by ',')");
    const std::string name = trim(entry.substr(0, colon));
    const std::string value = trim(entry.substr(colon + 1));
    const auto it = std::find(joints.begin(), joints.end(), name);
    if (it == joints.end())
      ctx.param_error("joint_offsets_deg", "unknown joint '" + name + "'" +
                                               did_you_mean(name, joints) +
                                               " (movable joints of the robot)");
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != value.size() || !std::isfinite(v))
      ctx.param_error("joint_offsets_deg",
                      "joint '" + name + "': expected a number [deg], got '" + value + "'");
    const int dof = static_cast<int>(it - joints.begin());
    const bool revolute = model_->joint(model_->dof_joint(dof)).type == robot::JointType::Revolute;
    offsets_[dof] = revolute ? v * M_PI / 180.0 : v;
  }

  skin_ = &ctx.input<SkinTaxels>("taxels");
  state_ = &ctx.input<JointState>("state");
  objects_ = &ctx.input<ObjectStates>("objects");
  link_poses_ = ctx.is_wired("link_poses") ? &ctx.input<LinkPoses>("link_poses") : nullptr;
  spawns_ = &ctx.output<ObjectSpawns>("spawns");
  stimulus_ = &ctx.output<Stimulus>("stimulus");
  truth_ = &ctx.output<Stimulus>("truth");
}

void ObjectThrower::launch(NodeContext& ctx) {
  const std::size_t index = static_cast<std::size_t>(launched_);
  const std::string& part = parts_[index % parts_.size()];
  const ObjectShape shape = shapes_[index % shapes_.size()];
  const SkinPart* sp = nullptr;
  for (const auto& p : skin_->parts)
    if (p.name == part) sp = &p;
  if (!sp || sp->taxel_ids.empty())
    throw RunError("skin part '" + part +
                   "' is not in the 'taxels' input (is the skin node wired?)");
  auto& rng = ctx.rng();
  std::uniform_int_distribution<std::size_t> pick(0, sp->taxel_ids.size() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t k = pick(rng);
  const Eigen::Vector3d n = sp->normals[k].normalized();
  // The centre's path ends one `size` above the taxel along its normal: the surface touches it.
  const Eigen::Vector3d target = sp->positions[k] + size_ * n;
  Eigen::Vector3d dir;
  double distance = 0.0;
  for (int attempt = 0;; ++attempt) {
    dir = sample_direction_in_cone(n, cone_rad_, rng);
    distance = distance_min_ + unit(rng) * (distance_max_ - distance_min_);
    // Start outside the robot (when its pose is known): redraw otherwise.
    if (!link_poses_ || robot::point_clear_of_robot(*model_, link_poses_->poses,
                                                    target + distance * dir, 2.0 * size_ + 0.01))
      break;
    if (attempt == 100)
      throw RunError("no start point clear of the robot for an object aimed at '" + part +
                     "' (lower 'distance_max' or 'cone')");
  }
  const double speed = speed_min_ + unit(rng) * (speed_max_ - speed_min_);

  ObjectSpawn spawn;
  spawn.id = next_spawn_id_++;
  spawn.name = "pps_object_" + std::to_string(spawn.id);
  spawn.shape = shape;
  spawn.size = shape == ObjectShape::kSphere ? Eigen::Vector3d(size_, 0, 0)
                                             : Eigen::Vector3d::Constant(size_);
  spawn.motion = ObjectMotion::kKinematic;
  spawn.pose = Eigen::Isometry3d::Identity();
  // A cube's face (its local +z) faces the taxel.
  spawn.pose.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n).toRotationMatrix();
  spawn.pose.translation() = target + distance * dir;
  spawn.linear_velocity = -speed * dir;
  const double travel = distance / speed;
  spawn.remove_after_s = travel + linger_;
  spawns_->recent.push_back(spawn);
  while (spawns_->recent.size() > 8) spawns_->recent.erase(spawns_->recent.begin());

  current_ = Approach{};
  current_.name = spawn.name;
  current_.part = part;
  current_.link = model_->link_index(sp->link);
  current_.taxel = sp->positions[k];
  current_.normal = n;
  current_.t_spawn = ctx.time_s();
  current_.travel = travel;
  current_.lifetime = spawn.remove_after_s;
  active_ = true;
  ++launched_;
  ++per_part_approaches_[part];
}

void ObjectThrower::perceive(NodeContext& ctx) {
  *truth_ = Stimulus{};
  *stimulus_ = Stimulus{};
  if (!active_) return;
  int obj = -1;
  for (std::size_t i = 0; i < objects_->names.size(); ++i)
    if (objects_->names[i] == current_.name) obj = static_cast<int>(i);
  const auto at = static_cast<std::size_t>(obj);
  if (obj < 0 || at >= objects_->present.size() || !objects_->present[at] ||
      at >= objects_->poses.size())
    return;
  truth_->present = true;
  truth_->position = objects_->poses[at].translation();
  truth_->velocity =
      at < objects_->linear_velocity.size() ? objects_->linear_velocity[at] : Eigen::Vector3d{};
  truth_->radius = size_;

  Eigen::VectorXd q = Eigen::VectorXd::Zero(model_->num_dofs());
  if (state_->position.size() != 0) q = state_->position;  // InputError below if mis-sized
  robot::forward_kinematics(*model_, *true_data_, q);
  robot::forward_kinematics(*model_, *believed_data_, q, offsets_);
  const Eigen::Isometry3d to_believed = robot::link_pose(*believed_data_, current_.link) *
                                        robot::link_pose(*true_data_, current_.link).inverse();

  auto& rng = ctx.rng();
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d p = truth_->position, v = truth_->velocity;
  if (position_noise_ > 0)
    for (int i = 0; i < 3; ++i) p[i] += position_noise_ * gauss(rng);
  if (velocity_noise_ > 0)
    for (int i = 0; i < 3; ++i) v[i] += velocity_noise_ * gauss(rng);
  stimulus_->present = true;
  stimulus_->position = to_believed * p;
  stimulus_->velocity = to_believed.linear() * v;  // a direction: rotation only
  stimulus_->radius = size_;

  // Perceived D at the aimed taxel at the moment of contact (the offset it should learn).
  if (!current_.contact_seen && ctx.time_s() - current_.t_spawn >= current_.travel - 1e-9) {
    current_.contact_seen = true;
    const Eigen::Vector3d rel = stimulus_->position - current_.taxel;
    const double z = rel.dot(current_.normal) - size_;
    const double tangential = (rel - rel.dot(current_.normal) * current_.normal).norm();
    const double d = std::copysign(std::hypot(z, tangential), z);
    contact_d_sum_[current_.part] += d;
    ++contact_d_count_[current_.part];
  }
}

void ObjectThrower::step(NodeContext& ctx) {
  const double now = ctx.time_s();
  if (active_ && now - current_.t_spawn >= current_.lifetime + pause_ - 1e-9) active_ = false;
  if (!active_) {
    if (launched_ >= approaches_) {
      *truth_ = Stimulus{};
      *stimulus_ = Stimulus{};
      ctx.request_stop(std::to_string(launched_) + " approaches done");
      return;
    }
    launch(ctx);
  }
  perceive(ctx);
}

void ObjectThrower::finish(NodeContext& ctx) {
  ctx.report_metric("approaches", launched_);
  nlohmann::json per_part = nlohmann::json::object();
  for (const auto& [part, n] : per_part_approaches_) {
    per_part[part] = {{"approaches", n}};
    const int c = contact_d_count_[part];
    if (c > 0) per_part[part]["contact_distance_mean_m"] = contact_d_sum_[part] / c;
  }
  ctx.report_metric("per_part", per_part);
}

}  // namespace somasim::plugins
