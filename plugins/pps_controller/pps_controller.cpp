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

PluginSpec PpsController::spec() {
  PluginSpec s("pps_controller",
               "Avoids or reaches what the peripersonal-space activations announce: taxels above "
               "the threshold vote a point P and normal N; that point of the arm moves along -N "
               "(avoid) or +N (reach) through a Cartesian velocity controller on the chain.");
  robot::add_robot_param(s);
  s.add_string("chain").describe("the named chain that moves (e.g. left_arm)");
  s.add_string("base")
      .defaults(std::string(""))
      .describe(
          "optional base link: only the joints of `chain` beyond it move (e.g. chest: the arm "
          "without the torso, so that two arm controllers do not share joints); '' = whole chain");
  s.add_string("mode")
      .defaults(std::string("avoid"))
      .one_of({"avoid", "reach"})
      .describe("avoid: move P along -N (away from the stimulus); reach: along +N (toward it)");
  s.add_string("reach_direction")
      .defaults(std::string("normal"))
      .one_of({"normal", "stimulus"})
      .describe(
          "reach mode: normal moves P along +N (the paper's rule); stimulus moves P straight "
          "toward the perceived stimulus (input 'stimulus'), which meets objects arriving off "
          "the normal with the skin first");
  s.add_string("body_part")
      .describe(
          "the skin part whose taxels vote (its link must be in the chain), e.g. left_forearm");
  s.add_double("threshold")
      .defaults(0.4)
      .range(0, 1)
      .describe("taxels with an activation above this vote");
  s.add_double("speed").unit_is("m/s").defaults(0.10).range(0, 10).describe(
      "speed of the controlled point");
  s.add_double("persistence")
      .unit_is("s")
      .defaults(0.3)
      .range(0, 1000)
      .describe("keep moving this long after the last above-threshold tick");
  s.add_double("return_after")
      .unit_is("s")
      .defaults(1.0)
      .range(0, 1000)
      .describe(
          "this long after the last above-threshold tick, return to the start posture (joint "
          "space)");
  s.add_double("workspace_radius")
      .unit_is("m")
      .defaults(0.2)
      .range(0, 10)
      .describe(
          "no point of the body part goes farther than this from where it was at the home "
          "posture (the controlled point stops at this distance)");
  s.add_double("return_gain")
      .unit_is("1/s")
      .defaults(2.0)
      .range(0, 1000)
      .describe("return home: joint velocity per radian of error");
  s.add_double("return_tolerance_deg")
      .unit_is("deg")
      .defaults(0.1)
      .range(0, 90)
      .describe("return home ends when every chain joint is this close to its start value");
  s.add_list("max_joint_velocity_deg")
      .unit_is("deg/s")
      .defaults(std::vector<double>{60.0})
      .at_least(0)
      .describe("joint speed limits: one value for all chain joints or one per joint");
  s.add_double("limit_margin_deg")
      .unit_is("deg")
      .defaults(2.0)
      .range(0, 90)
      .describe("joints stop this far from their limits");
  s.input<SkinTaxels>("taxels", "taxel poses in the root frame");
  s.input<TaxelValues>("activations",
                       "taxel activations: labelled 'part/id' (one or several parts; the "
                       "body part's taxels are picked by label), or unlabelled with one value "
                       "per taxel of the body part in the order of `taxels`");
  s.input<JointState>("state", "measured joint state");
  s.input<pps::Stimulus>("stimulus", "the perceived stimulus (for reach_direction: stimulus)",
                         /*optional=*/true);
  s.output<JointCommand>("command", "velocity commands on the chain dofs (kNone elsewhere)");
  s.output<Eigen::Vector3d>("point", "the last voted point P [m], root frame");
  s.output<Eigen::Vector3d>("velocity", "commanded velocity of the point [m/s], root frame");
  s.output<double>("triggered", "1 when a taxel is above the threshold this tick, else 0");
  return s;
}

void PpsController::configure(NodeContext& ctx) {
  model_ = robot::experiment_robot(ctx);
  control::ChainSelection chain;
  try {
    chain = control::select_chain(*model_, ctx.param<std::string>("chain"));
  } catch (const InputError& e) {
    ctx.param_error("chain", e.what());
  }
  if (const auto base = ctx.param<std::string>("base"); !base.empty()) {
    try {
      chain = control::select_chain(
          *model_, model_->find_chain(ctx.param<std::string>("chain"))->tip_frame, base);
    } catch (const InputError& e) {
      ctx.param_error("base", e.what());
    }
  }
  body_part_ = ctx.param<std::string>("body_part");
  reach_ = ctx.param<std::string>("mode") == "reach";
  threshold_ = ctx.param<double>("threshold");
  speed_ = ctx.param<double>("speed");
  persistence_ = ctx.param<double>("persistence");
  return_after_ = ctx.param<double>("return_after");
  radius_ = ctx.param<double>("workspace_radius");
  return_gain_ = ctx.param<double>("return_gain");
  return_tolerance_ = ctx.param<double>("return_tolerance_deg") * kDeg;

  control::CartesianVelocityOptions options;
  const auto max_deg = ctx.param<std::vector<double>>("max_joint_velocity_deg");
  options.max_joint_velocity =
      Eigen::Map<const Eigen::VectorXd>(max_deg.data(), static_cast<Eigen::Index>(max_deg.size())) *
      kDeg;
  options.limit_margin = ctx.param<double>("limit_margin_deg") * kDeg;
  const auto n_chain = static_cast<Eigen::Index>(chain.dofs.size());
  try {
    controller_ = std::make_unique<control::CartesianVelocityController>(model_, chain, options);
  } catch (const InputError& e) {
    ctx.param_error("max_joint_velocity_deg", e.what());
  }
  max_joint_velocity_ = options.max_joint_velocity.size() == 1
                            ? Eigen::VectorXd::Constant(n_chain, options.max_joint_velocity[0])
                            : options.max_joint_velocity;
  data_ = std::make_unique<robot::RobotData>(*model_);
  home_data_ = std::make_unique<robot::RobotData>(*model_);

  taxels_ = &ctx.input<SkinTaxels>("taxels");
  activations_ = &ctx.input<TaxelValues>("activations");
  state_ = &ctx.input<JointState>("state");
  if (reach_ && ctx.param<std::string>("reach_direction") == "stimulus") {
    if (!ctx.is_wired("stimulus"))
      ctx.param_error("reach_direction",
                      "'stimulus' needs the input 'stimulus' wired (e.g. thrower.stimulus)");
    stimulus_ = &ctx.input<pps::Stimulus>("stimulus");
  }
  command_ = &ctx.output<JointCommand>("command");
  point_ = &ctx.output<Eigen::Vector3d>("point");
  velocity_ = &ctx.output<Eigen::Vector3d>("velocity");
  triggered_ = &ctx.output<double>("triggered");
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
    if (p.name != body_part_) continue;
    if (link_ < 0) {
      try {
        link_ = controller_->chain().require_link(*model_, p.link);
      } catch (const InputError& e) {
        ctx.param_error("body_part", "skin part '" + body_part_ + "': " + e.what());
      }
    }
    return p;
  }
  std::vector<std::string> names;
  for (const auto& p : taxels_->parts) names.push_back(p.name);
  ctx.param_error("body_part", "no skin part '" + body_part_ + "' in the 'taxels' input" +
                                   did_you_mean(body_part_, names) +
                                   "; parts: " + join_names(names));
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
    throw RunError(ctx.node_name() + ": skin part '" + body_part_ +
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
  double sum = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), nrm = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] > threshold_)) continue;
    sum += a[i];
    p += a[i] * part.positions[i];
    nrm += a[i] * part.normals[i];
  }
  const bool triggered = sum > 0.0 && nrm.norm() > 1e-12;
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
                        ctx.node_name(), now, body_part_, d, radius_);
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
