#include "cartesian_velocity.hpp"

#include "somasim/robot/experiment_robot.hpp"

#include <cmath>
#include "somasim/units.hpp"

namespace somasim::plugins {

namespace {
constexpr double kDeg = kRadPerDeg;
}

PluginSpec CartesianVelocity::spec() {
  PluginSpec s("cartesian_velocity",
               "Moves a point of any link of a chain at a commanded Cartesian velocity: damped "
               "pseudo-inverse of the point's Jacobian, joint- and velocity-limit aware.");
  robot::add_robot_param(s);
  s.add_string("chain")
      .defaults(std::string())
      .describe(
          "a named chain of the robot (e.g. right_arm); or leave empty and give `tip` (and "
          "`base`)");
  s.add_string("base")
      .defaults(std::string())
      .describe("with `tip`: the chain's base link (empty: the root)");
  s.add_string("tip")
      .defaults(std::string())
      .describe("with `base`: the chain's tip frame or link (instead of `chain`)");
  s.add_string("link")
      .defaults(std::string())
      .describe(
          "the link the controlled point is fixed to; must be in the chain (empty: the tip's "
          "link)");
  s.add_list("point")
      .unit_is("m")
      .size(3)
      .defaults(std::vector<double>{0, 0, 0})
      .describe("the controlled point in the link frame");
  s.add_double("damping").unit_is("m").defaults(0.02).range(0, 1).describe(
      "largest damping λ of the pseudo-inverse (reached at a singularity)");
  s.add_double("singular_threshold")
      .unit_is("m")
      .defaults(0.04)
      .range(0, 10)
      .describe("damping ramps in when the Jacobian's smallest singular value falls below this");
  s.add_list("max_joint_velocity_deg")
      .unit_is("deg/s")
      .defaults(std::vector<double>{60.0})
      .at_least(0)
      .describe(
          "joint speed limits: one value for all chain joints or one per joint (base to tip); "
          "the whole solution is scaled down to respect them (direction kept)");
  s.add_double("limit_margin_deg")
      .unit_is("deg")
      .defaults(2.0)
      .range(0, 90)
      .describe("joints stop this far from their limits (clamped within the next period)");
  s.add_bool("hold_orientation")
      .defaults(false)
      .describe(
          "also keep the link's orientation (captured at the first step); else position only");
  s.add_double("orientation_gain")
      .unit_is("1/s")
      .defaults(2.0)
      .range(0, 1000)
      .describe("with hold_orientation: angular velocity per radian of orientation error");
  s.input<JointState>("state", "measured joint state");
  s.input<Eigen::Vector3d>("velocity", "desired velocity of the point [m/s], root frame");
  s.output<JointCommand>("command", "velocity commands on the chain dofs (kNone elsewhere)");
  s.output<Eigen::Vector3d>("point", "the controlled point [m], root frame");
  s.output<Eigen::Vector3d>("point_velocity",
                            "point velocity the command produces, J q̇ [m/s], root frame");
  s.output<double>("limited", "1 when a joint or velocity limit changed the command, else 0");
  return s;
}

void CartesianVelocity::configure(NodeContext& ctx) {
  auto model = robot::experiment_robot(ctx);
  const auto chain_name = ctx.param<std::string>("chain");
  const auto tip = ctx.param<std::string>("tip");
  const auto base = ctx.param<std::string>("base");
  if (chain_name.empty() && tip.empty())
    ctx.param_error("chain",
                    "expected a chain: give `chain` (a named chain of the robot) or `tip` "
                    "(and optionally `base`)");
  if (!chain_name.empty() && !tip.empty())
    ctx.param_error("tip", "give either `chain` or `tip` (and `base`), not both");
  if (!chain_name.empty() && !base.empty())
    ctx.param_error("base", "`base` goes with `tip`, not with `chain`");
  control::ChainSelection chain;
  try {
    chain = chain_name.empty() ? control::select_chain(*model, tip, base)
                               : control::select_chain(*model, chain_name);
  } catch (const InputError& e) {
    ctx.param_error(chain_name.empty() ? "tip" : "chain", e.what());
  }

  control::CartesianVelocityOptions options;
  options.damping = ctx.param<double>("damping");
  options.singular_threshold = ctx.param<double>("singular_threshold");
  const auto max_deg = ctx.param<std::vector<double>>("max_joint_velocity_deg");
  options.max_joint_velocity =
      Eigen::Map<const Eigen::VectorXd>(max_deg.data(), static_cast<Eigen::Index>(max_deg.size())) *
      kDeg;
  options.limit_margin = ctx.param<double>("limit_margin_deg") * kDeg;
  options.hold_orientation = ctx.param<bool>("hold_orientation");
  options.orientation_gain = ctx.param<double>("orientation_gain");
  try {
    controller_ = std::make_unique<control::CartesianVelocityController>(model, std::move(chain),
                                                                         std::move(options));
  } catch (const InputError& e) {
    ctx.param_error("max_joint_velocity_deg", e.what());
  }

  const auto link = ctx.param<std::string>("link");
  const auto p = ctx.param<std::vector<double>>("point");
  try {
    if (link.empty())
      controller_->set_point(controller_->link(), {p[0], p[1], p[2]});
    else
      controller_->set_point(link, {p[0], p[1], p[2]});
  } catch (const InputError& e) {
    ctx.param_error("link", e.what());
  }

  state_ = &ctx.input<JointState>("state");
  velocity_ = &ctx.input<Eigen::Vector3d>("velocity");
  command_ = &ctx.output<JointCommand>("command");
  point_ = &ctx.output<Eigen::Vector3d>("point");
  point_velocity_ = &ctx.output<Eigen::Vector3d>("point_velocity");
  limited_ = &ctx.output<double>("limited");
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
  ctx.report_metric("limited_fraction",
                    steps_ > 0 ? static_cast<double>(limited_steps_) / steps_ : 0.0);
}

}  // namespace somasim::plugins
