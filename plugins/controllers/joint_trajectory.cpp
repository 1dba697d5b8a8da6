#include "joint_trajectory.hpp"

#include "somasim/robot/experiment_robot.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include "somasim/units.hpp"

namespace somasim::plugins {

namespace {

// Degrees for revolute joints, metres for prismatic ones.
double to_joint_units(const robot::Joint& j, double value) {
  return j.type == robot::JointType::Prismatic ? value : deg_to_rad(value);
}
double from_joint_units(const robot::Joint& j, double value) {
  return j.type == robot::JointType::Prismatic ? value : rad_to_deg(value);
}

}  // namespace

template <class V>
void JointTrajectoryController::Config::visit(V& v) {
  v.block(robot);
  v.field("joints", joints)
      .doc("controlled joints (e.g. [r_shoulder_pitch, r_shoulder_roll, r_elbow])");
  v.field("targets_deg", targets_deg)
      .unit("deg")
      .doc(
          "waypoint targets, waypoint-major: len(durations) rows of len(joints) values (prismatic "
          "joints: metres); each within the joint limits");
  v.field("durations", durations)
      .unit("s")
      .at_least(1e-3)
      .doc("time to reach each waypoint from the previous one (the first: from the start)");
  v.field("profile", profile)
      .doc("time profile of every segment: linear or minimum_jerk (zero end velocities)");
  v.field("done_tolerance_deg", done_tolerance_deg)
      .unit("deg")
      .range(0, 180)
      .doc("> 0: `done` also waits until every measured joint is this close to the last waypoint");
}

void JointTrajectoryController::Config::validate(ConfigChecks& checks) const {
  for (auto it = joints.begin(); it != joints.end(); ++it)
    checks.require(std::find(joints.begin(), it, *it) == it, joints,
                   "joint '" + *it + "' is listed twice");
  checks.require(durations.empty() || !joints.empty(), joints,
                 "waypoints are given (durations) but no joints");
  const std::size_t nj = joints.size();
  checks.require(targets_deg.size() == durations.size() * nj, targets_deg,
                 "expected " + std::to_string(durations.size() * nj) + " values (" +
                     std::to_string(durations.size()) + " waypoints x " + std::to_string(nj) +
                     " joints, waypoint-major), got " + std::to_string(targets_deg.size()));
}

template <class V>
void JointTrajectoryController::Ports::visit(V& v) {
  v.port("state", state, "measured joint state (the start of the trajectory)");
  v.port("target", target, "new joint-space goals (optional; a new id starts a motion)");
  v.port("command", command,
         "position commands with velocity feed-forward on the controlled joints");
  v.port("done", done, "1 when the last waypoint (or target) is reached, else 0");
}

PluginSpec JointTrajectoryController::spec() {
  return make_plugin_spec<Config, Ports>(
      "joint_trajectory",
      "Joint-space trajectories (linear or minimum-jerk) through YAML waypoints or to targets on "
      "the `target` port; position commands with velocity feed-forward.");
}

void JointTrajectoryController::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  model_ = robot::experiment_robot(ctx, config_.robot);
  tolerance_ = deg_to_rad(config_.done_tolerance_deg);
  read_waypoints(ctx);
  bind_ports(ctx, ports_);
  const int n = model_->num_dofs();
  ports_.command->mode.assign(n, JointCommandMode::kNone);
  ports_.command->position.setZero(n);
  ports_.command->velocity.setZero(n);
  *ports_.done = 0.0;
}

void JointTrajectoryController::read_waypoints(const NodeContext& ctx) {
  const Config& c = config_;  // names unique and list sizes consistent: Config::validate()
  for (const std::string& name : c.joints) {
    int dof = -1;
    try {
      dof = model_->dof_index(name);
    } catch (const InputError& e) {
      config_error(ctx, c, c.joints, e.what());
    }
    joint_dofs_.push_back(dof);
  }
  const auto& targets = c.targets_deg;
  const auto& durations = c.durations;
  const std::size_t nj = joint_dofs_.size();
  for (std::size_t w = 0; w < durations.size(); ++w) {
    control::JointTrajectory::Waypoint wp;
    wp.duration_s = durations[w];
    wp.position.resize(static_cast<Eigen::Index>(nj));
    for (std::size_t k = 0; k < nj; ++k) {
      const int d = joint_dofs_[k];
      const robot::Joint& j = model_->joint(model_->dof_joint(d));
      const double q = to_joint_units(j, targets[w * nj + k]);
      const double lo = model_->lower_limits()[d], hi = model_->upper_limits()[d];
      if (q < lo - 1e-9 || q > hi + 1e-9)
        config_error(ctx, c, c.targets_deg,
                     fmt::format("waypoint {}, joint '{}': {:g} is outside the joint limits "
                                 "[{:g}, {:g}]",
                                 w, j.name, targets[w * nj + k], from_joint_units(j, lo),
                                 from_joint_units(j, hi)));
      wp.position[static_cast<Eigen::Index>(k)] = q;
    }
    waypoints_.push_back(std::move(wp));
  }
}

void JointTrajectoryController::start_target(double t, const JointState& state) {
  const JointTarget& target = *ports_.target;
  const auto n = static_cast<std::size_t>(model_->num_dofs());
  if (target.active.size() != n || static_cast<std::size_t>(target.position.size()) != n)
    throw RunError(
        fmt::format("joint_trajectory: target {} has {} active flags and {} positions, "
                    "expected {} (the dofs of robot '{}')",
                    target.id, target.active.size(), target.position.size(), n, model_->name()));
  if (!(target.duration_s > 0.0) || !target.position.allFinite())
    throw RunError(fmt::format(
        "joint_trajectory: target {} needs a positive duration and finite positions", target.id));
  // New motion on the joints already controlled plus the target's, from the current reference.
  std::set<int> dofs(active_dofs_.begin(), active_dofs_.end());
  for (std::size_t d = 0; d < n; ++d)
    if (target.active[d]) dofs.insert(static_cast<int>(d));
  std::vector<int> next(dofs.begin(), dofs.end());
  Eigen::VectorXd start(static_cast<Eigen::Index>(next.size()));
  control::JointTrajectory::Waypoint goal{start, target.duration_s};
  for (std::size_t k = 0; k < next.size(); ++k) {
    const int d = next[k];
    const auto it = std::find(active_dofs_.begin(), active_dofs_.end(), d);
    start[static_cast<Eigen::Index>(k)] =
        it != active_dofs_.end() ? reference_[it - active_dofs_.begin()] : state.position[d];
    goal.position[static_cast<Eigen::Index>(k)] =
        target.active[static_cast<std::size_t>(d)]
            ? std::clamp(target.position[d], model_->lower_limits()[d], model_->upper_limits()[d])
            : start[static_cast<Eigen::Index>(k)];
  }
  active_dofs_ = std::move(next);
  trajectory_ = control::JointTrajectory(config_.profile, t, std::move(start), {std::move(goal)});
  reference_.resize(static_cast<Eigen::Index>(active_dofs_.size()));
  reference_velocity_.resize(reference_.size());
  last_target_id_ = target.id;
  ++targets_received_;
}

void JointTrajectoryController::step(NodeContext& ctx) {
  const JointState& state = *ports_.state;
  const double t = ctx.time_s();
  if (state.position.size() == 0) return;  // the world has not reported yet
  robot::check_joint_state(ctx, *model_, state.position, state.velocity);
  if (!started_) {
    started_ = true;
    active_dofs_ = joint_dofs_;
    Eigen::VectorXd start(static_cast<Eigen::Index>(joint_dofs_.size()));
    for (std::size_t k = 0; k < joint_dofs_.size(); ++k)
      start[static_cast<Eigen::Index>(k)] = state.position[joint_dofs_[k]];
    trajectory_ = control::JointTrajectory(config_.profile, t, std::move(start), waypoints_);
    reference_.resize(static_cast<Eigen::Index>(active_dofs_.size()));
    reference_velocity_.resize(reference_.size());
    trajectory_.sample(t, reference_, reference_velocity_);
  }
  if (ports_.target.wired() && ports_.target->id != 0 && ports_.target->id != last_target_id_) {
    trajectory_.sample(t, reference_, reference_velocity_);  // the reference to start from
    start_target(t, state);
  }
  write_command(t, state);
}

void JointTrajectoryController::write_command(double t, const JointState& state) {
  trajectory_.sample(t, reference_, reference_velocity_);
  JointCommand& c = *ports_.command;
  std::fill(c.mode.begin(), c.mode.end(), JointCommandMode::kNone);
  bool reached = trajectory_.finished(t);
  for (std::size_t k = 0; k < active_dofs_.size(); ++k) {
    const int d = active_dofs_[k];
    const auto i = static_cast<Eigen::Index>(k);
    c.mode[static_cast<std::size_t>(d)] = JointCommandMode::kPosition;
    c.position[d] = reference_[i];
    c.velocity[d] = reference_velocity_[i];
    if (tolerance_ > 0.0 && std::abs(state.position[d] - reference_[i]) > tolerance_)
      reached = false;
  }
  *ports_.done = reached ? 1.0 : 0.0;
}

void JointTrajectoryController::finish(NodeContext& ctx) {
  ctx.report_metric("waypoints", static_cast<int>(waypoints_.size()));
  ctx.report_metric("targets_received", targets_received_);
  ctx.report_metric("done", ports_.done.bound() && *ports_.done == 1.0);
}

}  // namespace somasim::plugins
