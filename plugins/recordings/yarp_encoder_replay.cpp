#include "yarp_encoder_replay.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "somasim/recordings/yarp_bottle.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

template <class V>
void YarpEncoderReplay::Config::visit(V& v) {
  v.block(robot);
  v.block(log);
  v.field("joints", joints)
      .doc(
          "the robot joint of each value of a line, in order ('-' leaves a value out), e.g. "
          "[l_shoulder_pitch, l_shoulder_roll, l_shoulder_yaw, l_elbow, l_wrist_prosup, "
          "l_wrist_pitch, l_wrist_yaw] for the first 7 of /icub/left_arm/state:o");
  v.field("units", units).doc("unit of revolute joints' values: deg (YARP's encoders) or rad");
  v.field("interpolation", interpolation)
      .doc(
          "between two messages: linear (state and velocity from the two) or hold (the last "
          "message, zero velocity)");
}

template <class V>
void YarpEncoderReplay::Ports::visit(V& v) {
  v.port("state", state, "the recorded joint state (unmapped joints 0)");
  v.port("command", command,
         "position commands with velocity feed-forward on the mapped joints (mode none on the "
         "others), to drive the simulated robot along the recording");
}

PluginSpec YarpEncoderReplay::spec() {
  return make_plugin_spec<Config, Ports>(
      "yarp_encoder_replay",
      "Replays joint encoders recorded by yarpdatadumper (e.g. /icub/left_arm/state:o) as the "
      "robot's joint state and as position commands at their recorded times.");
}

void YarpEncoderReplay::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  model_ = robot::experiment_robot(ctx, config_.robot);
  bind_ports(ctx, ports_);
  map_joints(ctx);
  log_ = read_replay_log(ctx, config_, config_.log, recordings::DumpContent::kBottle);
  decode(ctx);
  cursor_ = std::make_unique<recordings::ReplayCursor>(log_.entries, config_.log.offset_s);
  log_timeline(ctx, log_);
  const int n = model_->num_dofs();
  ports_.state->position.setZero(n);
  ports_.state->velocity.setZero(n);
  ports_.command->mode.assign(static_cast<std::size_t>(n), JointCommandMode::kNone);
  ports_.command->position.setZero(n);
  ports_.command->velocity.setZero(n);
}

void YarpEncoderReplay::map_joints(NodeContext& ctx) {
  if (config_.joints.empty())
    config_error(ctx, config_, config_.joints,
                 "expected the robot joint of each value of a line ('-' to leave one out)");
  for (const std::string& name : config_.joints) {
    if (name == "-") {
      value_dof_.push_back(-1);
      continue;
    }
    int dof = -1;
    try {
      dof = model_->dof_index(name);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.joints, e.what());
    }
    if (std::find(mapped_dofs_.begin(), mapped_dofs_.end(), dof) != mapped_dofs_.end())
      config_error(ctx, config_, config_.joints, fmt::format("joint '{}' is listed twice", name));
    value_dof_.push_back(dof);
    mapped_dofs_.push_back(dof);
  }
  if (mapped_dofs_.empty())
    config_error(ctx, config_, config_.joints, "every value is left out ('-'): nothing to replay");
}

void YarpEncoderReplay::decode(NodeContext& ctx) {
  const std::string file = (log_.folder / "data.log").string();
  recordings::ReplayCursor timing(log_.entries, config_.log.offset_s);
  for (const recordings::DumpEntry& e : log_.entries) {
    recordings::BottleList values;
    try {
      values = recordings::parse_bottle(e.content, e.content_column);
    } catch (const recordings::BottleSyntaxError& err) {
      config_error(ctx, config_, config_.log.log,
                   fmt::format("{}:{}:{}: {}", file, e.line, err.column(), err.what()));
    }
    if (values.size() < value_dof_.size())
      config_error(ctx, config_, config_.log.log,
                   fmt::format("{}:{}:{}: expected at least {} values (one per entry of 'joints'), "
                               "got {}",
                               file, e.line, e.content_column, value_dof_.size(), values.size()));
    Eigen::VectorXd sample(static_cast<Eigen::Index>(mapped_dofs_.size()));
    Eigen::Index k = 0;
    for (std::size_t i = 0; i < value_dof_.size(); ++i) {
      if (value_dof_[i] < 0) continue;
      const recordings::BottleValue& v = values[i];
      if (!v.is_number() || !std::isfinite(v.number()))
        config_error(
            ctx, config_, config_.log.log,
            fmt::format("{}:{}:{}: value {} (joint '{}') must be a finite number, got {}", file,
                        e.line, v.column, i + 1, config_.joints[i],
                        v.is_number() ? "a non-finite number" : recordings::kind_name(v.kind)));
      const int dof = value_dof_[i];
      const robot::Joint& joint = model_->joint(model_->dof_joint(dof));
      double q = v.number();
      if (joint.type != robot::JointType::Prismatic && config_.units == AngleUnit::kDegrees)
        q = deg_to_rad(q);
      if (q < model_->lower_limits()[dof] - 1e-9 || q > model_->upper_limits()[dof] + 1e-9)
        ++outside_limits_;
      sample[k++] = q;
    }
    samples_.push_back(std::move(sample));
    due_s_.push_back(timing.due_time(e));
  }
}

void YarpEncoderReplay::step(NodeContext& ctx) {
  const double t = ctx.time_s();
  cursor_->advance_to(t);  // counts delivered messages
  // The last message due at or before t (index `i`), and the next one.
  const auto next = std::upper_bound(due_s_.begin(), due_s_.end(), t + 1e-9);
  const std::size_t j = static_cast<std::size_t>(next - due_s_.begin());
  const std::size_t i = j == 0 ? 0 : j - 1;
  Eigen::VectorXd q = samples_[i];
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(q.size());
  if (config_.interpolation == ReplayInterpolation::kLinear && j > 0 && j < samples_.size()) {
    const double span = due_s_[j] - due_s_[i];
    if (span > 0.0) {
      dq = (samples_[j] - samples_[i]) / span;
      q = samples_[i] + dq * (t - due_s_[i]);
    }
  }
  JointState& state = *ports_.state;
  JointCommand& command = *ports_.command;
  for (std::size_t k = 0; k < mapped_dofs_.size(); ++k) {
    const int dof = mapped_dofs_[k];
    const auto kk = static_cast<Eigen::Index>(k);
    state.position[dof] = q[kk];
    state.velocity[dof] = dq[kk];
    command.mode[static_cast<std::size_t>(dof)] = JointCommandMode::kPosition;
    command.position[dof] =
        std::clamp(q[kk], model_->lower_limits()[dof], model_->upper_limits()[dof]);
    command.velocity[dof] = dq[kk];
  }
}

void YarpEncoderReplay::finish(NodeContext& ctx) {
  if (!cursor_) return;
  report_replay(ctx, log_, *cursor_);
  ctx.report_metric("samples_outside_limits", outside_limits_);
}

}  // namespace somasim::plugins
