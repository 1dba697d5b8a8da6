#include "pps_controller.hpp"

#include "workspace_guard.hpp"

#include <algorithm>
#include <cmath>

#include "somasim/diagnostics.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

namespace {
constexpr double kDeg = kRadPerDeg;
constexpr double kTimeEps = 1e-9;
}  // namespace

template <class V>
void PpsController::Config::visit(V& v) {
  v.block(robot);
  v.field("chain", chain).required().doc("the named chain that moves (e.g. left_arm)");
  v.field("base", base)
      .doc(
          "optional base link: only the joints of `chain` beyond it move (e.g. chest: the arm "
          "without the torso, so that two arm controllers do not share joints); '' = whole chain");
  v.field("mode", mode)
      .doc("avoid: move P along -N (away from the stimulus); reach: along +N (toward it)");
  v.field("reach_direction", reach_direction)
      .doc(
          "reach mode: normal moves P along +N (the paper's rule); stimulus moves P straight "
          "toward the perceived stimulus (input 'stimulus'), which meets objects arriving off "
          "the normal with the skin first");
  v.field("body_part", body_part)
      .required()
      .doc("the skin part whose taxels vote (its link must be in the chain), e.g. left_forearm");
  v.field("threshold", threshold).range(0, 1).doc("taxels with an activation above this vote");
  v.field("speed", speed).unit("m/s").range(0, 10).doc("speed of the controlled point");
  v.field("trigger_hold_s", trigger_hold_s)
      .unit("s")
      .range(0, 10)
      .doc(
          "taxels vote only once some taxel of the part has stayed above the threshold this "
          "long without a break: a transient of the perceived stimulus shorter than this (one "
          "camera frame: 0.05 s at 20 Hz) moves nothing; 0 = at the first tick above (the "
          "paper's rule)");
  v.field("trigger_at_once_above", trigger_at_once_above)
      .range(0, 1)
      .doc(
          "an activation above this votes at once, without waiting trigger_hold_s: an object "
          "seen late and close is not held back, a marginal transient still is; 1 = every "
          "crossing waits the hold");
  v.field("persistence", persistence)
      .unit("s")
      .range(0, 1000)
      .doc("keep moving this long after the last above-threshold tick");
  v.field("return_after", return_after)
      .unit("s")
      .range(0, 1000)
      .doc(
          "this long after the last above-threshold tick, return to the start posture (joint "
          "space)");
  v.field("workspace_radius", workspace_radius)
      .unit("m")
      .range(0, 10)
      .doc(
          "no point of the body part goes farther than this from where it was at the home "
          "posture (the controlled point stops at this distance)");
  v.field("return_gain", return_gain)
      .unit("1/s")
      .range(0, 1000)
      .doc("return home: joint velocity per radian of error");
  v.field("return_tolerance_deg", return_tolerance_deg)
      .unit("deg")
      .range(0, 90)
      .doc("return home ends when every chain joint is this close to its start value");
  v.field("max_joint_velocity_deg", max_joint_velocity_deg)
      .unit("deg/s")
      .at_least(0)
      .doc("joint speed limits: one value for all chain joints or one per joint");
  v.field("hold_orientation", hold_orientation)
      .doc(
          "move the body part without turning it (the point's velocity and a zero angular "
          "velocity of its link, a 6-row task): a hand next to the voting taxels then moves as "
          "they do instead of swinging ahead of them; false = the point alone (the paper's "
          "rule)");
  v.field("limit_margin_deg", limit_margin_deg)
      .unit("deg")
      .range(0, 90)
      .doc("joints stop this far from their limits");
}

template <class V>
void PpsController::Ports::visit(V& v) {
  v.port("taxels", taxels, "taxel poses in the root frame");
  v.port("activations", activations,
         "taxel activations: labelled 'part/id' (one or several parts; the "
         "body part's taxels are picked by label), or unlabelled with one value "
         "per taxel of the body part in the order of `taxels`");
  v.port("state", state, "measured joint state");
  v.port("stimulus", stimulus, "the perceived stimulus (for reach_direction: stimulus)");
  v.port("command", command, "velocity commands on the chain dofs (kNone elsewhere)");
  v.port("point", point, "the last voted point P [m], root frame");
  v.port("velocity", velocity, "commanded velocity of the point [m/s], root frame");
  v.port("triggered", triggered, "1 when a taxel is above the threshold this tick, else 0");
}

PluginSpec PpsController::spec() {
  return make_plugin_spec<Config, Ports>(
      "pps_controller",
      "Avoids or reaches what the peripersonal-space activations announce: taxels above "
      "the threshold vote a point P and normal N; that point of the arm moves along -N "
      "(avoid) or +N (reach) through a Cartesian velocity controller on the chain.");
}

void PpsController::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  control::ChainSelection chain;
  try {
    chain = control::select_chain(*model_, config_.chain);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.chain, e.what());
  }
  if (const auto base = config_.base; !base.empty()) {
    try {
      chain = control::select_chain(*model_, model_->find_chain(config_.chain)->tip_frame, base);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.base, e.what());
    }
  }
  reach_ = config_.mode == PpsMode::kReach;
  threshold_ = config_.threshold;
  trigger_ = pps::HeldTrigger(config_.trigger_hold_s);
  at_once_above_ = config_.trigger_at_once_above;
  speed_ = config_.speed;
  persistence_ = config_.persistence;
  return_after_ = config_.return_after;
  radius_ = config_.workspace_radius;
  return_gain_ = config_.return_gain;
  return_tolerance_ = config_.return_tolerance_deg * kDeg;

  control::CartesianVelocityOptions options;
  const auto max_deg = config_.max_joint_velocity_deg;
  options.max_joint_velocity =
      Eigen::Map<const Eigen::VectorXd>(max_deg.data(), static_cast<Eigen::Index>(max_deg.size())) *
      kDeg;
  options.limit_margin = config_.limit_margin_deg * kDeg;
  options.hold_orientation = config_.hold_orientation;
  const auto n_chain = static_cast<Eigen::Index>(chain.dofs.size());
  try {
    controller_ = std::make_unique<control::CartesianVelocityController>(model_, chain, options);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.max_joint_velocity_deg, e.what());
  }
  max_joint_velocity_ = options.max_joint_velocity.size() == 1
                            ? Eigen::VectorXd::Constant(n_chain, options.max_joint_velocity[0])
                            : options.max_joint_velocity;
  data_ = std::make_unique<robot::RobotData>(*model_);
  home_data_ = std::make_unique<robot::RobotData>(*model_);

  taxels_ = &ports_.taxels.get();
  activations_ = &ports_.activations.get();
  state_ = &ports_.state.get();
  if (reach_ && config_.reach_direction == ReachDirection::kStimulus) {
    if (!ports_.stimulus.wired())
      config_error(ctx, config_, config_.reach_direction,
                   "'stimulus' needs the input 'stimulus' wired (e.g. thrower.stimulus)");
    stimulus_ = ports_.stimulus.get();
  }
  command_ = &ports_.command.get();
  point_ = &ports_.point.get();
  velocity_ = &ports_.velocity.get();
  triggered_ = &ports_.triggered.get();
  const int n = model_->num_dofs();
  command_->mode.assign(n, JointCommandMode::kNone);
  command_->position.setZero(n);
  command_->velocity.setZero(n);
  point_->setZero();
  velocity_->setZero();
  *triggered_ = 0.0;
}

const SkinPart& PpsController::find_part(NodeContext& ctx) {
  for (const auto& p : taxels_->parts) {
    if (p.name != config_.body_part) continue;
    if (link_ < 0) {
      try {
        link_ = controller_->chain().require_link(*model_, p.link);
      } catch (const InputError& e) {
        config_error(ctx, config_, config_.body_part,
                     "skin part '" + config_.body_part + "': " + e.what());
      }
    }
    return p;
  }
  std::vector<std::string> names;
  for (const auto& p : taxels_->parts) names.push_back(p.name);
  config_error(ctx, config_, config_.body_part,
               "no skin part '" + config_.body_part + "' in the 'taxels' input" +
                   did_you_mean(config_.body_part, names) + "; parts: " + join_names(names));
}

void PpsController::hold(const Eigen::VectorXd& q) {
  // In position mode at the posture where the hold began: a zero velocity target alone lets
  // the arm sag under gravity (the motors' torque is bounded), out of the workspace too.
  if (!holding_) hold_q_ = q;
  holding_ = true;
  for (int d : controller_->chain().dofs) {
    command_->mode[static_cast<std::size_t>(d)] = JointCommandMode::kPosition;
    command_->position[d] = hold_q_[d];
    command_->velocity[d] = 0.0;
  }
}

void PpsController::move(NodeContext& ctx, const Eigen::VectorXd& q) {
  // The controlled point now and at the start posture; the step along the direction is cut
  // where it would leave the workspace sphere around the home position.
  const Eigen::Vector3d now = data_->link_poses[link_] * point_link_;
  const Eigen::Vector3d home = home_data_->link_poses[link_] * point_link_;
  const Eigen::Vector3d e = now - home;
  const double dt = ctx.period_s();
  const double ed = e.dot(direction_);
  const double r2 = radius_ * radius_;
  double step = speed_ * dt;
  if (e.squaredNorm() >= r2) {
    if (ed >= 0.0) step = 0.0;  // at (or past) the boundary: only inward motion
  } else {
    step = std::min(step, -ed + std::sqrt(std::max(0.0, ed * ed - e.squaredNorm() + r2)));
  }
  *velocity_ = direction_ * (step / dt);
  controller_->set_point(link_, point_link_);
  controller_->compute(q, *velocity_, dt, *command_);
  // The step above holds the controlled point to the sphere as if the arm moved exactly as
  // asked; the guard holds every point of the part, as the joints will really move.
  const double scale =
      guard_->limit(q, controller_->chain().dofs, *command_, kGuardHorizonTicks * dt);
  *velocity_ *= scale;
  away_from_home_ = true;
  if (scale < kBlockedScale) {  // at the boundary, pushing out: hold there
    velocity_->setZero();
    hold(q);
    return;
  }
  holding_ = false;
}

void PpsController::return_home(const Eigen::VectorXd& q, double period_s) {
  const auto& dofs = controller_->chain().dofs;
  double worst = 0.0;
  for (std::size_t k = 0; k < dofs.size(); ++k)
    worst = std::max(worst, std::abs(home_q_[dofs[k]] - q[dofs[k]]));
  if (worst <= return_tolerance_) {
    away_from_home_ = false;
    hold(q);
    return;
  }
  holding_ = false;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const int d = dofs[k];
    const double limit = max_joint_velocity_[static_cast<Eigen::Index>(k)];
    command_->mode[static_cast<std::size_t>(d)] = JointCommandMode::kVelocity;
    command_->position[d] = q[d];
    command_->velocity[d] = std::clamp(return_gain_ * (home_q_[d] - q[d]), -limit, limit);
  }
  guard_->limit(q, dofs, *command_, kGuardHorizonTicks * period_s);
}

void PpsController::step(NodeContext& ctx) {
  const Eigen::VectorXd& q = state_->position;
  if (q.size() == 0) return;  // the world has not reported yet
  const int n = model_->num_dofs();
  if (q.size() != n || state_->velocity.size() != n)
    throw RunError(ctx.node_name() + ": joint state has " + std::to_string(q.size()) +
                   " positions and " + std::to_string(state_->velocity.size()) +
                   " velocities, expected " + std::to_string(n) + " (the dofs of robot '" +
                   model_->name() + "')");
  if (!q.allFinite()) throw RunError(ctx.node_name() + ": joint state holds non-finite positions");
  const SkinPart& part = find_part(ctx);
  const std::span<const double> a = part_activations_.select(*activations_, part, ctx.node_name());
  if (part.positions.size() != part.taxel_ids.size() ||
      part.normals.size() != part.taxel_ids.size())
    throw RunError(ctx.node_name() + ": skin part '" + config_.body_part +
                   "' has positions or normals missing for some taxels");

  if (!have_home_) {
    home_q_ = q;
    robot::forward_kinematics(*model_, *home_data_, home_q_);
    have_home_ = true;
    // Every taxel of the part, in the link frame: the points the workspace holds.
    std::vector<Eigen::Vector3d> points = part.positions_link;
    if (points.size() != part.positions.size()) {
      points.clear();
      const Eigen::Isometry3d to_link = home_data_->link_poses[link_].inverse();
      for (const auto& p : part.positions) points.push_back(to_link * p);
    }
    guard_ = std::make_unique<WorkspaceGuard>(model_, link_, std::move(points), home_q_,
                                              std::max(radius_ - kGuardMargin, 0.5 * radius_));
  }
  robot::forward_kinematics(*model_, *data_, q);
  const double now = ctx.time_s();

  // Vote.
  double sum = 0.0, peak = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), nrm = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] > threshold_)) continue;
    sum += a[i];
    peak = std::max(peak, a[i]);
    p += a[i] * part.positions[i];
    nrm += a[i] * part.normals[i];
  }
  const bool above = sum > 0.0 && nrm.norm() > 1e-12;
  const bool triggered = trigger_.update(now, above, above && peak > at_once_above_);
  if (triggered) {
    p /= sum;
    *point_ = p;
    point_link_ = data_->link_poses[link_].inverse() * p;
    direction_ = (reach_ ? 1.0 : -1.0) * nrm.normalized();
    if (stimulus_ && stimulus_->present && (stimulus_->position - p).norm() > kMinAimDistance)
      direction_ = (stimulus_->position - p).normalized();
    have_target_ = true;
    last_trigger_s_ = now;
    if (!was_triggered_) ++triggers_;
    ++triggered_ticks_;
  }
  was_triggered_ = triggered;
  *triggered_ = triggered ? 1.0 : 0.0;

  velocity_->setZero();
  const double since = now - last_trigger_s_;
  if (have_target_ && (triggered || since < persistence_ - kTimeEps)) {
    move(ctx, q);
  } else {
    have_target_ = false;
    if (away_from_home_ && since >= return_after_ - kTimeEps)
      return_home(q, ctx.period_s());
    else
      hold(q);
  }
  if (away_from_home_ || have_target_) {
    const double d = guard_->max_distance(q);
    if (d > radius_ + kOutsideTolerance) {
      if (outside_ticks_ == 0 || d > max_distance_)
        ctx.log().debug("{}: t = {:.3f} s, a point of '{}' is {:.4f} m from home (radius {} m)",
                        ctx.node_name(), now, config_.body_part, d, radius_);
      ++outside_ticks_;
    }
    max_distance_ = std::max(max_distance_, d);
  }
}

void PpsController::finish(NodeContext& ctx) {
  ctx.report_metric("triggers", triggers_);
  ctx.report_metric("triggered_time_s", static_cast<double>(triggered_ticks_) * ctx.period_s());
  ctx.report_metric("max_distance_from_home_m", max_distance_);
  // Time any point of the part spent beyond the radius (+1 mm): the physics lagging behind.
  ctx.report_metric("outside_workspace_s", static_cast<double>(outside_ticks_) * ctx.period_s());
}

}  // namespace somasim::plugins

SOMASIM_PLUGIN_LIBRARY(registrar) {
  registrar.add<somasim::plugins::PpsController>();
}
