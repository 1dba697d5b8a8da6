#include "double_touch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "somasim/control/trajectory.hpp"
#include "somasim/diagnostics.hpp"
#include "somasim/random_directions.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/units.hpp"

namespace somasim::plugins {

namespace {

constexpr double kDeg = kRadPerDeg;

Eigen::Vector3d vec3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}

}  // namespace

void DoubleTouch::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  true_data_ = std::make_unique<robot::RobotData>(*model_);
  believed_data_ = std::make_unique<robot::RobotData>(*model_);

  const robot::SkinPatch* patch = nullptr;
  std::vector<std::string> parts;
  for (const auto& p : model_->skin_patches()) {
    parts.push_back(p.body_part);
    if (p.body_part == config_.body_part) patch = &p;
  }
  if (!patch)
    config_error(ctx, config_, config_.body_part,
                 "unknown skin part '" + config_.body_part + "'" +
                     did_you_mean(config_.body_part, parts) +
                     "; the robot's skin parts: " + join_names(parts));
  try {
    effector_ = model_->frame_ref(config_.effector);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.effector, e.what());
  }
  const Eigen::Vector3d axis = vec3(config_.effector_axis);
  effector_axis_link_ = effector_.pose.linear() * axis.normalized();
  const Eigen::Vector3d side = vec3(config_.effector_side);
  limb_axis_ = vec3(config_.limb_axis);
  const Eigen::Vector3d side_link = effector_.pose.linear() * side;
  finger_tilt_ = config_.finger_tilt_deg * kDeg;

  speed_min_ = config_.speed_min;
  speed_max_ = config_.speed_max;
  position_jitter_ = config_.position_jitter;
  normal_jitter_ = config_.normal_jitter_deg * kDeg;
  move_duration_ = config_.move_duration;
  hold_ = config_.hold;
  finger_radius_ = config_.finger_radius;
  position_noise_ = config_.position_noise;
  velocity_noise_ = config_.velocity_noise;
  seen_by_eyes_ = config_.perception == FingertipPerception::kVision;
  try {
    home_ = robot::parse_posture_deg(*model_, config_.home_posture_deg);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.home_posture_deg, e.what());
  }
  for (const std::string& t : config_.taxels) {
    std::size_t used = 0;
    int id = -1;
    try {
      id = std::stoi(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != t.size() || id < 0)
      config_error(ctx, config_, config_.taxels,
                   "expected taxel ids (integers >= 0), got '" + t + "'");
    taxel_list_.push_back(id);
  }

  control::TouchPlannerOptions po;
  po.start_distance = config_.start_distance;
  po.press_depth = config_.press_depth;
  po.step = config_.approach_step;
  po.align_distance = config_.align_distance;
  po.max_tilt = config_.max_tilt_deg * kDeg;
  po.clearance = config_.clearance;
  try {
    control::TouchIkOptions io;
    io.position_tolerance = 1e-4;  // waypoints this close to the normal line
    io.posture_gain = 0.03;        // a gentle pull: fewer jumps along the approach
    control::TouchIk ik(model_, effector_, effector_axis_link_, side_link, patch->link, {}, io);
    planner_ = std::make_unique<control::TouchPlanner>(model_, std::move(ik), po);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.effector, e.what());
  }

  plan_data_ = std::make_unique<robot::RobotData>(*model_);
  measure_ = [this](const Eigen::VectorXd& q) {
    // The planned fingertip's distance from the aimed point along the aimed normal.
    robot::forward_kinematics(*model_, *plan_data_, q);
    const Eigen::Isometry3d& t =
        plan_data_->link_poses[static_cast<std::size_t>(planner_->ik().target_link())];
    const Eigen::Vector3d tip = robot::frame_pose(*plan_data_, effector_).translation();
    return (tip - t * aimed_link_).dot(t.linear() * aimed_normal_link_);
  };
  state_ = &ports_.state.get();
  taxels_ = &ports_.taxels.get();
  contacts_ = ports_.contacts.get();
  believed_state_ = ports_.believed_state.get();
  believed_taxels_ = ports_.believed_taxels.get();
  command_ = &ports_.command.get();
  stimulus_ = &ports_.stimulus.get();
  truth_ = &ports_.truth.get();
  true_offsets_ = &ports_.true_offsets.get();
}

const SkinPart& DoubleTouch::part(NodeContext&) const {
  for (const auto& p : taxels_->parts)
    if (p.name == config_.body_part) {
      if (p.taxel_ids.empty() || p.positions_link.size() != p.taxel_ids.size() ||
          p.normals_link.size() != p.taxel_ids.size())
        break;
      return p;
    }
  throw RunError("skin part '" + config_.body_part +
                 "' (with link-frame taxel poses) is not in the 'taxels' input (is the skin node "
                 "wired?)");
}

bool DoubleTouch::plan_touch(NodeContext& ctx) {
  const SkinPart& p = part(ctx);
  auto& rng = ctx.rng();
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto plan_at = [&](std::size_t k, bool jitter) {
    control::TouchTarget target;
    const Eigen::Vector3d n = p.normals_link[k].normalized();
    target.point = p.positions_link[k];
    target.normal = n;
    if (jitter) {
      const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
      // One draw per statement (the order of the operands' evaluation is unspecified), in the
      // order g++ drew them, which the published runs used.
      const double a2 = gauss(rng);
      const double a1 = gauss(rng);
      target.point += position_jitter_ * (a1 * t1 + a2 * t2);
      target.normal = sample_direction_in_cone(n, normal_jitter_, rng);
    }
    target.tilt = finger_tilt_;
    std::string detail;
    control::PlanResult r = control::PlanResult::kUnreachable;
    // The other fingers may lie on either side of the limb: try both.
    for (const double sign : {1.0, -1.0}) {
      target.tangent = sign * limb_axis_.cross(target.normal);
      r = planner_->plan(target, home_, q_ref_, path_, detail);
      ctx.log().debug("taxel {}, fingers toward {:+.0f}: {}", p.taxel_ids[k], sign,
                      r == control::PlanResult::kOk ? "ok" : detail);
      if (r == control::PlanResult::kOk) {
        aimed_link_ = target.point;
        aimed_normal_link_ = target.normal.normalized();
        return true;
      }
    }
    (r == control::PlanResult::kUnreachable ? ik_failures_ : collision_rejections_) +=
        jitter ? 1 : 0;
    return false;
  };
  constexpr int kAttempts = 20;
  if (!taxel_list_.empty()) {
    const int id = taxel_list_[static_cast<std::size_t>(next_in_list_++) % taxel_list_.size()];
    const auto it = std::find(p.taxel_ids.begin(), p.taxel_ids.end(), id);
    if (it == p.taxel_ids.end())
      throw RunError("taxel " + std::to_string(id) + " is not a taxel of '" + config_.body_part +
                     "' (" + std::to_string(p.taxel_ids.size()) + " taxels)");
    const auto k = static_cast<std::size_t>(it - p.taxel_ids.begin());
    for (int a = 0; a < kAttempts; ++a)
      if (plan_at(k, true)) {
        planned_taxel_ = static_cast<int>(k);
        return true;
      }
    throw RunError("taxel " + std::to_string(id) + " of '" + config_.body_part +
                   "' cannot be touched from the home posture (" + std::to_string(kAttempts) +
                   " attempts; see the log)");
  }
  if (reachable_.empty()) {
    // Once: the taxels the fingertip can reach along their normals from home, clear of the arms.
    for (std::size_t k = 0; k < p.taxel_ids.size(); ++k)
      if (plan_at(k, false)) reachable_.push_back(k);
    if (reachable_.empty())
      throw RunError("no taxel of '" + config_.body_part +
                     "' can be touched from the home posture (see the log at debug level)");
  }
  std::uniform_int_distribution<std::size_t> pick(0, reachable_.size() - 1);
  for (int a = 0; a < kAttempts; ++a) {
    const std::size_t k = reachable_[pick(rng)];
    if (plan_at(k, true)) {
      planned_taxel_ = static_cast<int>(k);
      return true;
    }
  }
  throw RunError("no touch could be planned in " + std::to_string(kAttempts) +
                 " draws (lower position_jitter or normal_jitter_deg)");
}

void DoubleTouch::start_transfer(double now, const Eigen::VectorXd& goal) {
  transfer_from_ = q_ref_;
  transfer_to_ = goal;
  phase_start_ = now;
}

void DoubleTouch::advance(NodeContext& ctx) {
  const double now = ctx.time_s();
  for (int guard = 0; guard < 8; ++guard) {
    const double elapsed = now - phase_start_;
    switch (phase_) {
      case Phase::kPlan:
        ctx.report_progress(static_cast<std::int64_t>(log_.size()), config_.touches, "touches");
        if (static_cast<int>(log_.size()) >= config_.touches) {
          start_transfer(now, home_);
          phase_ = Phase::kHome;
          continue;
        }
        plan_touch(ctx);
        start_transfer(now, path_.posture.front());
        phase_ = Phase::kTransfer;
        continue;
      case Phase::kTransfer:
      case Phase::kHome: {
        const auto p =
            control::sample_profile(control::Profile::kMinimumJerk, elapsed / move_duration_);
        q_ref_ = transfer_from_ + p.s * (transfer_to_ - transfer_from_);
        dq_ref_ = (p.ds / move_duration_) * (transfer_to_ - transfer_from_);
        if (elapsed < move_duration_ - 1e-9) return;
        if (phase_ == Phase::kHome) {
          phase_ = Phase::kDone;
          ctx.request_stop(std::to_string(log_.size()) + " touches done");
          return;
        }
        Touch t;
        t.taxel_id = part(ctx).taxel_ids[static_cast<std::size_t>(planned_taxel_)];
        t.speed = speed_min_ + std::uniform_real_distribution<double>(0.0, 1.0)(ctx.rng()) *
                                   (speed_max_ - speed_min_);
        t.t_approach = now;
        log_.push_back(t);
        phase_ = Phase::kApproach;
        phase_start_ = now;
        continue;
      }
      case Phase::kApproach: {
        const double v = log_.back().speed;
        const double d = path_.start() - v * elapsed;
        Eigen::VectorXd dq_dd;
        path_.sample(d, measure_, q_ref_, &dq_dd);
        dq_ref_ = -v * dq_dd;
        if (d > path_.end()) return;
        phase_ = Phase::kHold;
        phase_start_ = now;
        continue;
      }
      case Phase::kHold:
        q_ref_ = path_.posture.back();
        dq_ref_.setZero(q_ref_.size());
        if (elapsed < hold_ - 1e-9) return;
        {
          // Control accuracy: the true fingertip against the aimed point, along the skin.
          const robot::FrameRef& e = effector_;
          const Eigen::Vector3d tip = robot::frame_pose(*true_data_, e).translation();
          const int link = planner_->ik().target_link();
          const Eigen::Isometry3d& tl = true_data_->link_poses[static_cast<std::size_t>(link)];
          const SkinPart& p = part(ctx);
          const Eigen::Vector3d n =
              tl.linear() * p.normals_link[static_cast<std::size_t>(planned_taxel_)].normalized();
          const Eigen::Vector3d rel = tip - tl * aimed_link_;
          log_.back().final_error = (rel - rel.dot(n) * n).norm();
        }
        phase_ = Phase::kRetreat;
        phase_start_ = now;
        continue;
      case Phase::kRetreat: {
        const double d = path_.end() + speed_max_ * elapsed;
        Eigen::VectorXd dq_dd;
        path_.sample(d, measure_, q_ref_, &dq_dd);
        dq_ref_ = speed_max_ * dq_dd;
        if (d < path_.start()) return;
        log_.back().t_end = now;
        phase_ = Phase::kPlan;
        continue;
      }
      case Phase::kDone:
        dq_ref_.setZero(q_ref_.size());
        return;
    }
  }
}

void DoubleTouch::perceive(NodeContext& ctx) {
  const Eigen::VectorXd& q = state_->position;
  robot::forward_kinematics(*model_, *true_data_, q);  // InputError names the size mismatch
  const bool believed = believed_state_ && believed_state_->position.size() == q.size();
  robot::forward_kinematics(*model_, *believed_data_, believed ? believed_state_->position : q);
  const auto centre = [&](const robot::RobotData& data) {
    const Eigen::Isometry3d& link = data.link_poses[static_cast<std::size_t>(effector_.link)];
    return Eigen::Vector3d(link * effector_.pose.translation() -
                           finger_radius_ * (link.linear() * effector_axis_link_));
  };
  // Proprioception: the fingertip ball of the believed arm. Vision: the marker on the true
  // fingertip, as ideal eyes see it (the arm's offsets do not enter).
  const Eigen::Vector3d pt = centre(*true_data_);
  const Eigen::Vector3d pb =
      seen_by_eyes_ ? Eigen::Vector3d(robot::frame_pose(*true_data_, effector_).translation())
                    : centre(*believed_data_);
  const double perceived_radius = seen_by_eyes_ ? config_.marker_radius : finger_radius_;
  const double dt = ctx.period_s();
  const Eigen::Vector3d vb =
      have_last_ ? Eigen::Vector3d((pb - last_perceived_) / dt) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d vt =
      have_last_ ? Eigen::Vector3d((pt - last_true_) / dt) : Eigen::Vector3d::Zero();
  last_perceived_ = pb;
  last_true_ = pt;
  have_last_ = true;

  const bool present = phase_ == Phase::kApproach || phase_ == Phase::kHold;
  perceived_clean_ = pps::Stimulus{pb, vb, perceived_radius, true};
  truth_clean_ = pps::Stimulus{pt, vt, finger_radius_, true};
  path_history_.push_back({ctx.time_s(), perceived_clean_, truth_clean_});
  while (path_history_.front().time_s < ctx.time_s() - pps::kOffsetMaxBackoff)
    path_history_.pop_front();
  *truth_ = pps::Stimulus{pt, vt, finger_radius_, present};
  *stimulus_ = pps::Stimulus{pb, vb, perceived_radius, present};
  auto& rng = ctx.rng();
  std::normal_distribution<double> gauss(0.0, 1.0);
  if (position_noise_ > 0)
    for (int i = 0; i < 3; ++i) stimulus_->position[i] += position_noise_ * gauss(rng);
  if (velocity_noise_ > 0)
    for (int i = 0; i < 3; ++i) stimulus_->velocity[i] += velocity_noise_ * gauss(rng);
  if (!present) {
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    *stimulus_ = pps::Stimulus{zero, zero, perceived_radius, false};
    *truth_ = pps::Stimulus{zero, zero, finger_radius_, false};
  }
}

void DoubleTouch::read_contacts(NodeContext&) {
  if (!contacts_) return;
  const bool touching =
      phase_ == Phase::kApproach || phase_ == Phase::kHold || phase_ == Phase::kRetreat;
  for (const auto& e : contacts_->recent) {
    if (e.id <= last_event_id_) continue;
    last_event_id_ = e.id;
    if (e.body_part == config_.body_part) {
      ++events_on_part_;
      if (touching && !log_.empty()) {
        Touch& t = log_.back();
        t.reached_skin = true;
        if (std::find(e.touched_taxels.begin(), e.touched_taxels.end(), t.taxel_id) !=
            e.touched_taxels.end())
          t.on_aimed_taxel = true;
      } else {
        ++events_outside_touches_;
      }
    } else {
      ++events_elsewhere_;
    }
    add_true_offsets(e);
  }
}

void DoubleTouch::add_true_offsets(const ContactEvent& e) {
  // The fingertip's path is curved and slows down toward the skin: the offsets are taken on
  // the recorded path, where the true tip was pps::kOffsetClearance outside the taxel.
  const std::vector<pps::PathSample> path(path_history_.begin(), path_history_.end());
  true_offset_samples_ += offsets_.add_event_on_path(
      e, *taxels_, believed_taxels_ ? *believed_taxels_ : *taxels_, path, pps::kOffsetClearance);
}

void DoubleTouch::write_command() {
  const int n = model_->num_dofs();
  if (command_->mode.size() != static_cast<std::size_t>(n)) {
    command_->mode.assign(static_cast<std::size_t>(n), JointCommandMode::kNone);
    for (int d : planner_->ik().solved_dofs())
      command_->mode[static_cast<std::size_t>(d)] = JointCommandMode::kPosition;
  }
  command_->position = q_ref_;
  command_->velocity = dq_ref_;
}

void DoubleTouch::step(NodeContext& ctx) {
  if (!started_) {
    if (state_->position.size() != model_->num_dofs())
      throw RunError("'state' has " + std::to_string(state_->position.size()) +
                     " joint values, expected " + std::to_string(model_->num_dofs()) +
                     " (is it wired to the world's joint_state?)");
    q_ref_ = state_->position;
    dq_ref_ = Eigen::VectorXd::Zero(q_ref_.size());
    started_ = true;
  }
  offsets_.sync_layout(*taxels_);
  perceive(ctx);
  read_contacts(ctx);
  offsets_.write(*true_offsets_);
  advance(ctx);
  write_command();
}

void DoubleTouch::finish(NodeContext& ctx) {
  int reached = 0, on_aimed = 0, measured = 0;
  double err_sum = 0.0, err_max = 0.0;
  nlohmann::json per_touch = nlohmann::json::array();
  for (const auto& t : log_) {
    reached += t.reached_skin ? 1 : 0;
    on_aimed += t.on_aimed_taxel ? 1 : 0;
    nlohmann::json j = {{"taxel", t.taxel_id},
                        {"speed_m_s", t.speed},
                        {"reached_skin", t.reached_skin},
                        {"on_aimed_taxel", t.on_aimed_taxel}};
    if (t.final_error >= 0) {
      ++measured;
      err_sum += t.final_error;
      err_max = std::max(err_max, t.final_error);
      j["final_error_m"] = t.final_error;
    }
    per_touch.push_back(j);
  }
  ctx.report_metric("touches", static_cast<int>(log_.size()));
  ctx.report_metric("touches_reached_skin", reached);
  ctx.report_metric("touches_on_aimed_taxel", on_aimed);
  ctx.report_metric("ik_failures", ik_failures_);
  ctx.report_metric("collision_rejections", collision_rejections_);
  ctx.report_metric("reachable_taxels", static_cast<int>(reachable_.size()));
  ctx.report_metric("events_on_part", events_on_part_);
  ctx.report_metric("events_outside_touches", events_outside_touches_);
  ctx.report_metric("events_elsewhere", events_elsewhere_);
  if (measured > 0) {
    ctx.report_metric("final_error_mean_m", err_sum / measured);
    ctx.report_metric("final_error_max_m", err_max);
  }
  ctx.report_metric("true_offset_samples", true_offset_samples_);
  ctx.report_metric("per_touch", per_touch);
}

}  // namespace somasim::plugins
