#include "believed_kinematics.hpp"

#include <cmath>
#include <random>

#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

template <class V>
void BelievedKinematics::Config::visit(V& v) {
  v.block(robot);
  v.field("joint_offsets_deg", joint_offsets_deg)
      .map_as_text()
      .doc(
          "believed-kinematics error, 'joint: value, ...' [deg] (prismatic: [m]) added to the "
          "true joint values");
  v.field("encoder_noise_deg", encoder_noise_deg)
      .unit("deg")
      .range(0, 90)
      .doc("Gaussian encoder noise (σ per revolute joint, drawn every tick)");
}

template <class V>
void BelievedKinematics::Ports::visit(V& v) {
  v.port("state", true_state, "true joint values (e.g. bullet_world.joint_state)");
  v.port("taxels", true_taxels,
         "true skin taxel poses (e.g. skin.taxels); their link-frame fields are used");
  v.port("state", state, "believed joint values: true + offsets + noise; velocities as measured");
  v.port("link_poses", link_poses, "link poses by the believed kinematics (root <- link)");
  v.port("taxels", taxels,
         "the skin taxels posed by the believed kinematics (root frame; link-frame fields copied)");
}

PluginSpec BelievedKinematics::spec() {
  return make_plugin_spec<Config, Ports>(
      "believed_kinematics",
      "What the robot believes of its own body: the true joint values plus injected offsets and "
      "encoder noise, the link poses and skin taxel poses they give (forward kinematics of the "
      "robot model).");
}

void BelievedKinematics::configure(NodeContext& ctx) {
  const auto config = read_config<Config>(ctx);
  model_ = robot::experiment_robot(ctx, config.robot);
  try {
    offsets_ = robot::parse_joint_offsets(*model_, config.joint_offsets_deg);
  } catch (const InputError& e) {
    config_error(ctx, config, config.joint_offsets_deg, e.what());
  }
  const double sigma = deg_to_rad(config.encoder_noise_deg);
  for (int d = 0; d < model_->num_dofs(); ++d)
    noise_sigma_.push_back(
        model_->joint(model_->dof_joint(d)).type == robot::JointType::Revolute ? sigma : 0.0);
  data_ = std::make_unique<robot::RobotData>(*model_);
  bind_ports(ctx, ports_);
}

void BelievedKinematics::step(NodeContext& ctx) {
  const Eigen::VectorXd& q = ports_.true_state->position;
  if (q.size() == 0) return;  // nothing measured yet: nothing believed yet
  const int n = model_->num_dofs();
  if (q.size() != n)
    throw RunError("input 'state': expected " + std::to_string(n) + " joint values (robot '" +
                   model_->name() + "'), got " + std::to_string(q.size()));
  ports_.state->position = q + offsets_;
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int d = 0; d < n; ++d)
    if (noise_sigma_[static_cast<std::size_t>(d)] > 0.0)
      ports_.state->position[d] += noise_sigma_[static_cast<std::size_t>(d)] * gauss(ctx.rng());
  ports_.state->velocity = ports_.true_state->velocity;
  robot::forward_kinematics(*model_, *data_, ports_.state->position);
  ports_.link_poses->poses = data_->link_poses;
  if (ports_.true_taxels) pose_taxels();
}

void BelievedKinematics::pose_taxels() {
  const auto& parts = ports_.true_taxels->parts;
  ports_.taxels->parts.resize(parts.size());
  part_links_.resize(parts.size(), -1);
  part_link_names_.resize(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const SkinPart& in = parts[i];
    SkinPart& out = ports_.taxels->parts[i];
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
