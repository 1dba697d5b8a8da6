#include "cartesian_velocity.hpp"

#include "somasim/robot/experiment_robot.hpp"

#include <cmath>
#include "somasim/units.hpp"

namespace somasim::plugins {

namespace {
constexpr double kDeg = kRadPerDeg;
}

template <class V>
void CartesianVelocity::Config::visit(V& v) {
  v.block(robot);
  v.field("chain", chain)
      .doc(
          "a named chain of the robot (e.g. right_arm); or leave empty and give `tip` (and "
          "`base`)");
  v.field("base", base).doc("with `tip`: the chain's base link (empty: the root)");
  v.field("tip", tip).doc("with `base`: the chain's tip frame or link (instead of `chain`)");
  v.field("link", link)
      .doc(
          "the link the controlled point is fixed to; must be in the chain (empty: the tip's "
          "link)");
  v.field("point", point).unit("m").size(3).doc("the controlled point in the link frame");
  v.field("damping", damping)
      .unit("m")
      .range(0, 1)
      .doc("largest damping λ of the pseudo-inverse (reached at a singularity)");
  v.field("singular_threshold", singular_threshold)
      .unit("m")
      .range(0, 10)
      .doc("damping ramps in when the Jacobian's smallest singular value falls below this");
  v.field("max_joint_velocity_deg", max_joint_velocity_deg)
      .unit("deg/s")
      .at_least(0)
      .doc(
          "joint speed limits: one value for all chain joints or one per joint (base to tip); "
          "the whole solution is scaled down to respect them (direction kept)");
  v.field("limit_margin_deg", limit_margin_deg)
      .unit("deg")
      .range(0, 90)
      .doc("joints stop this far from their limits (clamped within the next period)");
  v.field("hold_orientation", hold_orientation)
      .doc("also keep the link's orientation (captured at the first step); else position only");
  v.field("orientation_gain", orientation_gain)
      .unit("1/s")
      .range(0, 1000)
      .doc("with hold_orientation: angular velocity per radian of orientation error");
}

template <class V>
void CartesianVelocity::Ports::visit(V& v) {
  v.port("state", state, "measured joint state");
  v.port("velocity", velocity, "desired velocity of the point [m/s], root frame");
  v.port("command", command, "velocity commands on the chain dofs (kNone elsewhere)");
  v.port("point", point, "the controlled point [m], root frame");
  v.port("point_velocity", point_velocity,
         "point velocity the command produces, J q̇ [m/s], root frame");
  v.port("limited", limited, "1 when a joint or velocity limit changed the command, else 0");
}

void CartesianVelocity::Config::validate(ConfigChecks& checks) const {
  checks.require(!chain.empty() || !tip.empty(), chain,
                 "expected a chain: give `chain` (a named chain of the robot) or `tip` "
                 "(and optionally `base`)");
  checks.require(chain.empty() || tip.empty(), tip,
                 "give either `chain` or `tip` (and `base`), not both");
  checks.require(chain.empty() || base.empty(), base, "`base` goes with `tip`, not with `chain`");
}

PluginSpec CartesianVelocity::spec() {
  return make_plugin_spec<Config, Ports>(
      "cartesian_velocity",
      "Moves a point of any link of a chain at a commanded Cartesian velocity: damped "
      "pseudo-inverse of the point's Jacobian, joint- and velocity-limit aware.");
}

void CartesianVelocity::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  auto model = robot::experiment_robot(ctx, config_.robot);
  const auto chain_name = config_.chain;
  const auto tip = config_.tip;
  const auto base = config_.base;
  control::ChainSelection chain;
  try {
    chain = chain_name.empty() ? control::select_chain(*model, tip, base)
                               : control::select_chain(*model, chain_name);
  } catch (const InputError& e) {
    if (chain_name.empty()) config_error(ctx, config_, config_.tip, e.what());
    config_error(ctx, config_, config_.chain, e.what());
  }

  control::CartesianVelocityOptions options;
  options.damping = config_.damping;
  options.singular_threshold = config_.singular_threshold;
  const auto max_deg = config_.max_joint_velocity_deg;
  options.max_joint_velocity =
      Eigen::Map<const Eigen::VectorXd>(max_deg.data(), static_cast<Eigen::Index>(max_deg.size())) *
      kDeg;
  options.limit_margin = config_.limit_margin_deg * kDeg;
  options.hold_orientation = config_.hold_orientation;
  options.orientation_gain = config_.orientation_gain;
  try {
    controller_ = std::make_unique<control::CartesianVelocityController>(model, std::move(chain),
                                                                         std::move(options));
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.max_joint_velocity_deg, e.what());
  }

  const auto link = config_.link;
  const auto p = config_.point;
  try {
    if (link.empty())
      controller_->set_point(controller_->link(), {p[0], p[1], p[2]});
    else
      controller_->set_point(link, {p[0], p[1], p[2]});
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.link, e.what());
  }

  state_ = &ports_.state.get();
  velocity_ = &ports_.velocity.get();
  command_ = &ports_.command.get();
  point_ = &ports_.point.get();
  point_velocity_ = &ports_.point_velocity.get();
  limited_ = &ports_.limited.get();
  const int n = model->num_dofs();
  command_->mode.assign(n, JointCommandMode::kNone);
  command_->position.setZero(n);
  command_->velocity.setZero(n);
  point_->setZero();
  point_velocity_->setZero();
  *limited_ = 0.0;
}

void CartesianVelocity::step(NodeContext& ctx) {
  if (state_->position.size() == 0) return;  // the world has not reported yet
  robot::check_joint_state(ctx, controller_->model(), state_->position, state_->velocity);
  if (!velocity_->allFinite())
    throw RunError(ctx.node_name() + ": non-finite commanded velocity on port 'velocity'");
  controller_->compute(state_->position, *velocity_, ctx.period_s(), *command_);
  *point_ = controller_->point_position();
  *point_velocity_ = controller_->predicted_velocity();
  *limited_ = controller_->limited() ? 1.0 : 0.0;
  ++steps_;
  if (controller_->limited()) ++limited_steps_;
}

void CartesianVelocity::finish(NodeContext& ctx) {
  ctx.report_metric(
      "limited_fraction",
      steps_ > 0 ? static_cast<double>(limited_steps_) / static_cast<double>(steps_) : 0.0);
}

}  // namespace somasim::plugins
