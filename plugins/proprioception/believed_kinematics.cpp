#include "believed_kinematics.hpp"

#include <cmath>
#include <random>

#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

PluginSpec BelievedKinematics::spec() {
  PluginSpec s("believed_kinematics",
               "What the robot believes of its own body: the true joint values plus injected "
               "offsets and encoder noise, the link poses and skin taxel poses they give "
               "(forward kinematics of the robot model).");
  robot::add_robot_param(s);
  s.add_string("joint_offsets_deg")
      .accepts_map_as_text()
      .defaults(std::string(""))
      .describe(
          "believed-kinematics error, 'joint: value, ...' [deg] (prismatic: [m]) added to the "
          "true joint values");
  s.add_double("encoder_noise_deg")
      .unit_is("deg")
      .defaults(0.0)
      .range(0, 90)
      .describe("Gaussian encoder noise (σ per revolute joint, drawn every tick)");
  s.input<JointState>("state", "true joint values (e.g. bullet_world.joint_state)");
  s.input<SkinTaxels>("taxels",
                      "true skin taxel poses (e.g. skin.taxels); their link-frame fields are used",
                      /*optional=*/true);
  s.output<JointState>("state",
                       "believed joint values: true + offsets + noise; velocities as measured");
  s.output<LinkPoses>("link_poses", "link poses by the believed kinematics (root <- link)");
  s.output<SkinTaxels>("taxels",
                       "the skin taxels posed by the believed kinematics (root frame; link-frame "
                       "fields copied)");
  return s;
}

void BelievedKinematics::configure(NodeContext& ctx) {
  model_ = robot::experiment_robot(ctx);
  try {
    offsets_ = robot::parse_joint_offsets(*model_, ctx.param<std::string>("joint_offsets_deg"));
  } catch (const InputError& e) {
    ctx.param_error("joint_offsets_deg", e.what());
  }
  const double sigma = deg_to_rad(ctx.param<double>("encoder_noise_deg"));
  for (int d = 0; d < model_->num_dofs(); ++d)
    noise_sigma_.push_back(
        model_->joint(model_->dof_joint(d)).type == robot::JointType::Revolute ? sigma : 0.0);
  data_ = std::make_unique<robot::RobotData>(*model_);
  true_state_ = &ctx.input<JointState>("state");
  true_taxels_ = ctx.is_wired("taxels") ? &ctx.input<SkinTaxels>("taxels") : nullptr;
  state_ = &ctx.output<JointState>("state");
  link_poses_ = &ctx.output<LinkPoses>("link_poses");
  taxels_ = &ctx.output<SkinTaxels>("taxels");
}

void BelievedKinematics::step(NodeContext& ctx) {
  const Eigen::VectorXd& q = true_state_->position;
  if (q.size() == 0) return;  // nothing measured yet: nothing believed yet
  const int n = model_->num_dofs();
  if (q.size() != n)
    throw RunError("input 'state': expected " + std::to_string(n) + " joint values (robot '" +
                   model_->name() + "'), got " + std::to_string(q.size()));
  state_->position = q + offsets_;
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int d = 0; d < n; ++d)
    if (noise_sigma_[static_cast<std::size_t>(d)] > 0.0)
      state_->position[d] += noise_sigma_[static_cast<std::size_t>(d)] * gauss(ctx.rng());
  state_->velocity = true_state_->velocity;
  robot::forward_kinematics(*model_, *data_, state_->position);
  link_poses_->poses = data_->link_poses;
  if (true_taxels_) pose_taxels();
}

void BelievedKinematics::pose_taxels() {
  const auto& parts = true_taxels_->parts;
  taxels_->parts.resize(parts.size());
  part_links_.resize(parts.size(), -1);
  part_link_names_.resize(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const SkinPart& in = parts[i];
    SkinPart& out = taxels_->parts[i];
    if (part_links_[i] < 0 || part_link_names_[i] != in.link) {
      const int link = model_->find_link(in.link);
      if (link < 0)
        throw RunError("input 'taxels': skin part '" + in.name + "' is on link '" + in.link +
                       "', which robot '" + model_->name() + "' does not have");
      part_links_[i] = link;
      part_link_names_[i] = in.link;
    }
    const std::size_t count = in.taxel_ids.size();
    if (in.positions_link.size() != count || in.normals_link.size() != count)
      throw RunError("input 'taxels': skin part '" + in.name + "' has " + std::to_string(count) +
                     " taxels but " + std::to_string(in.positions_link.size()) +
                     " link-frame positions and " + std::to_string(in.normals_link.size()) +
                     " link-frame normals");
    out.name = in.name;
    out.link = in.link;
    out.taxel_ids = in.taxel_ids;
    out.positions_link = in.positions_link;
    out.normals_link = in.normals_link;
    out.positions.resize(count);
    out.normals.resize(count);
    const Eigen::Isometry3d& pose = data_->link_poses[static_cast<std::size_t>(part_links_[i])];
    for (std::size_t k = 0; k < count; ++k) {
      out.positions[k] = pose * in.positions_link[k];
      out.normals[k] = pose.linear() * in.normals_link[k];
    }
  }
}

}  // namespace somasim::plugins
