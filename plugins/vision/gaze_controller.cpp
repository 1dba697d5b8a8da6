#include "gaze_controller.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

template <class V>
void GazeController::Config::visit(V& v) {
  v.block(robot);
  v.field("cameras", cameras).size(2).doc("the two cameras whose optical axes meet at the target");
  v.field("neck_joints", neck_joints)
      .doc("joints that point the head (the coarse part of the gaze)");
  v.field("eye_joints", eye_joints).doc("joints that point the eyes (pulled weakly toward 0)");
  v.field("joint_offsets_deg", joint_offsets_deg)
      .map_as_text()
      .doc("believed-kinematics error, 'joint: value, ...' [deg] added to the encoders");
  v.field("max_speed_deg_s", max_speed_deg_s)
      .unit("deg/s")
      .range(1.0, 1000.0)
      .doc("largest commanded speed of a gaze joint");
  v.field("eye_centring", eye_centring)
      .range(0.0, 10.0)
      .doc("weight of the eyes' pull toward 0 in the gaze solve");
  v.field("reach_tolerance_deg", reach_tolerance_deg)
      .unit("deg")
      .range(0.0, 90.0)
      .doc("a target further than this from an optical axis at the solution is out of reach");
  v.field("idle", idle)
      .doc(
          "without a target: hold the gaze where it is; fixation: look at the mean of the "
          "believed centroids of idle_parts (between them); scan: look at each part's believed "
          "centroid in turn for dwell_s. Fixation and scan need the taxels input");
  v.field("idle_parts", idle_parts)
      .doc("skin parts of the taxels input that the idle fixation / scan looks at");
  v.field("hold_s", hold_s)
      .unit("s")
      .range(0.0, 100.0)
      .doc("the gaze stays on the last target for this long before it goes idle");
  v.field("dwell_s", dwell_s)
      .unit("s")
      .range(0.05, 100.0)
      .doc("idle scan: time on each part before the next");
}

void GazeController::Config::validate(ConfigChecks& checks) const {
  std::vector<std::string> all = neck_joints;
  all.insert(all.end(), eye_joints.begin(), eye_joints.end());
  for (auto it = all.begin(); it != all.end(); ++it) {
    const bool neck = static_cast<std::size_t>(it - all.begin()) < neck_joints.size();
    checks.require(std::find(all.begin(), it, *it) == it, neck ? neck_joints : eye_joints,
                   "joint '" + *it + "' is listed twice (neck_joints and eye_joints together)");
  }
  checks.require(cameras.size() != 2 || cameras[0] != cameras[1], cameras,
                 "the two cameras are the same ('" + (cameras.empty() ? "" : cameras[0]) + "')");
}

template <class V>
void GazeController::Ports::visit(V& v) {
  v.port("target", target, "what to look at (root frame), e.g. marker_tracker.stimulus");
  v.port("taxels", taxels,
         "the believed skin taxels (e.g. believed.taxels): where the idle fixation "
         "/ scan looks");
  v.port("joint_state", joint_state, "encoder values (e.g. world.joint_state)");
  v.port("command", command,
         "position commands of the gaze joints (encoder values); the other "
         "joints kNone (merge with a joint_command_mux)");
}

PluginSpec GazeController::spec() {
  return make_plugin_spec<Config, Ports>(
      "gaze_controller",
      "Neck and eyes follow a stimulus: the gaze joints that put it on both optical "
      "axes (believed kinematics: encoders + joint_offsets_deg), reached at a bounded "
      "joint speed with position commands within the joint limits. A target out of "
      "reach leaves joints at their limits, logged once per episode and counted "
      "(metrics out_of_reach_steps, max_gaze_offset_deg). Without a target for hold_s "
      "the gaze goes idle: it holds, looks at the middle of the believed skin parts "
      "(fixation) or at each of them in turn (scan), from the believed taxels only.");
}

void GazeController::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  vision::GazeOptions options;
  options.cameras = config_.cameras;
  options.neck_joints = config_.neck_joints;
  options.eye_joints = config_.eye_joints;
  options.eye_centring = config_.eye_centring;
  for (const auto* joints : {&config_.neck_joints, &config_.eye_joints})
    for (const std::string& joint : *joints) {
      try {
        model_->dof_index(joint);
      } catch (const InputError& e) {
        config_error(ctx, config_, *joints, fmt::format("gaze: {}", e.what()));
      }
    }
  try {
    solver_ = std::make_unique<vision::GazeSolver>(model_, options);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.cameras, e.what());  // the joints are checked above
  }
  // Every gaze joint must move a camera (lie between the root and a camera's link).
  for (const auto* joints : {&config_.neck_joints, &config_.eye_joints})
    for (const std::string& joint : *joints) {
      const int dof = model_->dof_index(joint);
      bool moves_a_camera = false;
      for (const std::string& c : config_.cameras) {
        const auto& dofs = model_->supporting_dofs(
            model_->cameras().at(static_cast<std::size_t>(model_->find_camera(c))).link);
        moves_a_camera = moves_a_camera || std::find(dofs.begin(), dofs.end(), dof) != dofs.end();
      }
      if (!moves_a_camera)
        config_error(ctx, config_, *joints,
                     fmt::format("gaze: joint '{}' moves neither camera ({}): it is not between "
                                 "the robot's root and the cameras' links",
                                 joint, fmt::join(config_.cameras, ", ")));
    }
  try {
    offsets_ = robot::parse_joint_offsets(*model_, config_.joint_offsets_deg);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.joint_offsets_deg, e.what());
  }
  const std::string_view idle = enum_name(config_.idle);
  hold_s_ = config_.hold_s;
  dwell_s_ = config_.dwell_s;
  if (config_.idle != GazeIdle::kHold && config_.idle_parts.empty())
    config_error(ctx, config_, config_.idle_parts,
                 fmt::format("idle '{}' needs at least one skin part", idle));
  if (config_.idle != GazeIdle::kHold && !ports_.taxels.wired())
    config_error(ctx, config_, config_.idle,
                 fmt::format("idle '{}' needs the input 'taxels' (the believed skin, "
                             "e.g. believed.taxels) wired",
                             idle));
  taxels_ = ports_.taxels.get();
  max_speed_ = deg_to_rad(config_.max_speed_deg_s);
  reach_tolerance_ = deg_to_rad(config_.reach_tolerance_deg);
  target_ = &ports_.target.get();
  joints_ = &ports_.joint_state.get();
  command_ = &ports_.command.get();
  const int n = model_->num_dofs();
  command_->mode.assign(static_cast<std::size_t>(n), JointCommandMode::kNone);
  command_->position.setZero(n);
  command_->velocity.setZero(n);
}

bool GazeController::part_centroids(std::vector<Eigen::Vector3d>& out) const {
  out.clear();
  if (taxels_ == nullptr || taxels_->parts.empty()) return false;  // nothing believed yet
  for (const std::string& name : config_.idle_parts) {
    const auto it = std::find_if(taxels_->parts.begin(), taxels_->parts.end(),
                                 [&](const SkinPart& p) { return p.name == name; });
    if (it == taxels_->parts.end()) {
      std::vector<std::string> have;
      for (const SkinPart& p : taxels_->parts) have.push_back(p.name);
      throw RunError(
          fmt::format("gaze_controller: idle_parts: no skin part '{}' in the input "
                      "'taxels' (it has: {})",
                      name, join(have)));
    }
    if (it->positions.empty()) return false;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : it->positions) sum += p;
    out.push_back(sum / static_cast<double>(it->positions.size()));
  }
  return true;
}

void GazeController::aim(NodeContext& ctx, const Eigen::VectorXd& q, const Eigen::Vector3d& point,
                         bool tracking) {
  const vision::GazeSolution s = solver_->solve(q + offsets_, point);
  goal_ = s.q - offsets_;
  if (!tracking) return;
  const bool unreachable = s.behind || s.residual_rad > reach_tolerance_;
  if (unreachable) {
    ++clamped_steps_;
    max_offset_rad_ = std::max(max_offset_rad_, s.residual_rad);
    if (!out_of_reach_)
      ctx.log().warn(
          "gaze_controller: target ({:.3f}, {:.3f}, {:.3f}) m is out of reach at t = {:.3f} s: "
          "{} at their limits, {:.1f} deg off the optical axes{}",
          point.x(), point.y(), point.z(), ctx.time_s(),
          s.at_limit.empty() ? std::string("no joint") : join(s.at_limit),
          rad_to_deg(s.residual_rad), s.behind ? " (behind a camera)" : "");
  }
  out_of_reach_ = unreachable;
}

void GazeController::step(NodeContext& ctx) {
  const Eigen::VectorXd& q = joints_->position;
  if (q.size() == 0) return;  // nothing measured yet
  if (q.size() != model_->num_dofs())
    throw RunError(fmt::format("input 'joint_state': expected {} joint values (robot '{}'), got {}",
                               model_->num_dofs(), model_->name(), q.size()));
  ++steps_;
  const double t = ctx.time_s();
  if (!started_) {  // hold the current gaze until there is something to look at
    goal_ = q;
    command_->position = q;
    for (const int d : solver_->dofs())
      command_->mode[static_cast<std::size_t>(d)] = JointCommandMode::kPosition;
    started_ = true;
    idle_since_s_ = t;
  }
  if (target_->present) {
    ++steps_with_target_;
    last_target_s_ = t;
    idle_now_ = false;
    aim(ctx, q, target_->position, /*tracking=*/true);
  } else if (config_.idle != GazeIdle::kHold && t - last_target_s_ >= hold_s_) {
    if (!idle_now_) {
      idle_now_ = true;
      idle_since_s_ = t;
      ++idle_entries_;
    }
    ++idle_steps_;
    std::vector<Eigen::Vector3d> centroids;
    if (part_centroids(centroids)) {
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      if (config_.idle == GazeIdle::kFixation) {
        for (const Eigen::Vector3d& c : centroids) point += c;
        point /= static_cast<double>(centroids.size());
      } else {
        const auto k = static_cast<std::size_t>(std::floor((t - idle_since_s_) / dwell_s_));
        point = centroids[k % centroids.size()];
      }
      aim(ctx, q, point, /*tracking=*/false);
      if (idle_steps_ == 1)
        ctx.log().info(
            "gaze_controller: idle ({}) at t = {:.3f} s: looking at ({:.3f}, {:.3f}, "
            "{:.3f}) m",
            enum_name(config_.idle), t, point.x(), point.y(), point.z());
    }
  }
  // Toward the goal at a bounded speed, within the limits.
  const double max_step = max_speed_ * ctx.period_s();
  for (const int d : solver_->dofs()) {
    double& c = command_->position[d];
    c += std::clamp(goal_[d] - c, -max_step, max_step);
    c = std::clamp(c, model_->lower_limits()[d], model_->upper_limits()[d]);
  }
}

void GazeController::finish(NodeContext& ctx) {
  ctx.report_metric("steps", steps_);
  ctx.report_metric("steps_with_target", steps_with_target_);
  ctx.report_metric("out_of_reach_steps", clamped_steps_);
  ctx.report_metric("idle_steps", idle_steps_);
  ctx.report_metric("idle_entries", idle_entries_);
  ctx.report_metric("max_gaze_offset_deg", rad_to_deg(max_offset_rad_));
}

}  // namespace somasim::plugins
