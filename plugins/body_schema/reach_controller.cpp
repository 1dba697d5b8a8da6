#include "reach_controller.hpp"

#include <fmt/format.h>

#include <numbers>
#include <random>

#include "somasim/body_schema/pose_error.hpp"
#include "somasim/error.hpp"
#include "somasim/robot/experiment_robot.hpp"

namespace somasim::plugins {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

Eigen::Isometry3d pose_from(const std::vector<double>& v, std::size_t i) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(v[i], v[i + 1], v[i + 2]);
  const Eigen::Vector3d r = Eigen::Vector3d(v[i + 3], v[i + 4], v[i + 5]) * kDegToRad;
  if (r.norm() > 0) t.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  return t;
}

}  // namespace

template <class V>
void ReachController::Config::visit(V& v) {
  v.block(robot);
  v.field("camera", camera).doc("the eye frame of the targets");
  v.field("palm_frame", palm_frame).doc("the controlled frame");
  v.field("arm_base", arm_base)
      .doc("link the arm chain starts from: the joints between it and the palm move");
  v.field("targets", targets)
      .doc(
          "desired palm poses in the eye frame, 6 numbers each: x y z [m], rotation "
          "vector rx ry rz [deg]");
  v.field("starts_per_target", starts_per_target)
      .range(1, 1000)
      .doc("start postures per target (drawn from the node's random stream)");
  v.field("repetitions", repetitions).range(1, 1000).doc("of each movement");
  v.field("start_distance", start_distance)
      .size(2)
      .unit("m")
      .doc("distance of the start palm position from the target's, uniform in [lo, hi]");
  v.field("start_rotation_deg", start_rotation_deg)
      .range(0.0, 90.0)
      .doc("largest rotation of the start palm orientation from the target's");
  v.field("to_start_frames", to_start_frames)
      .range(2, 100000)
      .doc("frames to move to a start posture and settle (not observed)");
  v.field("open_loop_frames", open_loop_frames).range(1, 100000).doc("");
  v.field("closed_loop_frames", closed_loop_frames).range(0, 100000).doc("");
  v.field("gain", gain).unit("1/s").at_least(0.0).doc("λ of the servo");
  v.field("adaptation", adaptation)
      .doc("closed loop with K(θ + β̂) (true) or the nominal model K(θ) (false)");
  v.field("csv", csv).doc("per-frame errors in the run folder ('' = none)");
}

template <class V>
void ReachController::Ports::visit(V& v) {
  v.port("joint_state", joint_state, "encoder readings θ");
  v.port("estimate", estimate, "the body_schema_filter's estimate (wire delayed)");
  v.port("true_link_poses", true_link_poses, "the world's link poses (the truth, for the errors)");
  v.port("command", command, "position targets of the arm joints (encoder values)");
  v.port("phase", phase, "movement, stage and frame (wire to the filter's phase)");
}

void ReachController::Config::validate(ConfigChecks& checks) const {
  checks.require(!targets.empty() && targets.size() % 6 == 0, targets,
                 fmt::format("expected 6 numbers per target (x y z [m], rx ry rz [deg]), got {} "
                             "numbers",
                             targets.size()));
  checks.require(start_distance[0] >= 0 && start_distance[0] <= start_distance[1], start_distance,
                 "expected 0 <= lo <= hi");
}

PluginSpec ReachController::spec() {
  return make_plugin_spec<Config, Ports>(
      "reach_controller",
      "Reaching with an adapted body schema (Vicente et al. 2016): per movement, a start "
      "posture, an open loop (linear joint trajectory to the nominal IK solution of the "
      "desired palm pose, in the left-eye frame) and a closed loop (position-based "
      "visual servoing q' = -gain J+(θ + β̂) e); errors against the truth, figures.");
}

void ReachController::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  try {
    eye_hand_ = std::make_unique<body_schema::EyeHand>(model_, config_.camera, config_.palm_frame,
                                                       config_.arm_base);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.palm_frame, e.what());
  }
  const auto targets = config_.targets;
  for (std::size_t i = 0; i < targets.size(); i += 6)
    targets_.push_back({pose_from(targets, i), {}, {}});
  starts_per_target_ = config_.starts_per_target;
  repetitions_ = config_.repetitions;
  to_start_frames_ = config_.to_start_frames;
  open_frames_ = config_.open_loop_frames;
  closed_frames_ = config_.closed_loop_frames;
  csv_name_ = config_.csv.name;
  if (!csv_name_.empty()) csv_path_ = config_.csv.path;
  movements_ = static_cast<int>(targets_.size()) * starts_per_target_ * repetitions_;

  joint_state_ = &ports_.joint_state.get();
  estimate_ = ports_.estimate.get();
  true_poses_ = ports_.true_link_poses.get();
  command_ = &ports_.command.get();
  command_->mode.assign(static_cast<std::size_t>(model_->num_dofs()), JointCommandMode::kNone);
  command_->position = Eigen::VectorXd::Zero(model_->num_dofs());
  command_->velocity = Eigen::VectorXd::Zero(model_->num_dofs());
  phase_ = &ports_.phase.get();
  report_ = std::make_unique<ReachReport>(open_frames_, closed_frames_);
}

Eigen::VectorXd ReachController::draw_start(NodeContext& ctx, const Target& target, int index) {
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> uniform;
  const robot::Camera& cam =
      model_->cameras()[static_cast<std::size_t>(model_->find_camera(config_.camera))];
  for (int attempt = 0; attempt < 200; ++attempt) {
    const Eigen::Vector3d dir =
        Eigen::Vector3d(gauss(ctx.rng()), gauss(ctx.rng()), gauss(ctx.rng())).normalized();
    const Eigen::Vector3d axis =
        Eigen::Vector3d(gauss(ctx.rng()), gauss(ctx.rng()), gauss(ctx.rng())).normalized();
    const double distance =
        config_.start_distance[0] +
        (config_.start_distance[1] - config_.start_distance[0]) * uniform(ctx.rng());
    const double angle = config_.start_rotation_deg * kDegToRad * uniform(ctx.rng());
    Eigen::Isometry3d start = target.pose_eye;
    start.translation() += distance * dir;
    start.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * start.linear();
    const Eigen::Vector3d p = start.translation();
    if (p.z() < 0.12) continue;
    const double u = cam.fx * p.x() / p.z() + cam.cx, v = cam.fy * p.y() / p.z() + cam.cy;
    if (u < visible_margin_px_ || u > cam.width - visible_margin_px_ || v < visible_margin_px_ ||
        v > cam.height - visible_margin_px_)
      continue;
    Eigen::VectorXd q = target.posture;
    const robot::IkResult r = eye_hand_->solve(start, q);
    if (r.success) return q;
  }
  throw RunError(
      fmt::format("reach_controller: found no reachable start pose in view for target "
                  "{} (start {}) in 200 draws; lower start_distance or "
                  "start_rotation_deg",
                  &target - targets_.data(), index));
}

void ReachController::plan_targets(NodeContext& ctx, const Eigen::VectorXd& q0) {
  for (std::size_t t = 0; t < targets_.size(); ++t) {
    Target& target = targets_[t];
    target.posture = q0;
    const robot::IkResult r = eye_hand_->solve(target.pose_eye, target.posture);
    if (!r.success) {
      const Eigen::Vector3d p = target.pose_eye.translation();
      config_error(ctx, config_, config_.targets,
                   fmt::format("target {} ({:.3f}, {:.3f}, {:.3f}) m in the {} frame is outside "
                               "the arm's reach: the closest palm pose found is {:.1f} mm and "
                               "{:.1f} deg away",
                               t, p.x(), p.y(), p.z(), config_.camera, r.position_error * 1e3,
                               r.orientation_error / kDegToRad));
    }
  }
  for (Target& target : targets_)
    for (int s = 0; s < starts_per_target_; ++s)
      target.starts.push_back(draw_start(ctx, target, s));
  ctx.log().info("reach_controller: {} targets x {} starts x {} repetitions = {} movements",
                 targets_.size(), starts_per_target_, repetitions_, movements_);
}

MovementId ReachController::movement_id(int movement) const {
  MovementId id;
  id.movement = movement;
  id.repetition = movement % repetitions_;
  id.start = (movement / repetitions_) % starts_per_target_;
  id.target = movement / (repetitions_ * starts_per_target_);
  return id;
}

void ReachController::command(const Eigen::VectorXd& q) {
  for (int d : eye_hand_->arm_dofs()) {
    command_->mode[static_cast<std::size_t>(d)] = JointCommandMode::kPosition;
    command_->position[d] = q[d];
  }
}

Eigen::VectorXd ReachController::adapted_offsets() const {
  if (estimate_ != nullptr && estimate_->movement == movement_ && estimate_->frame > 0 &&
      estimate_->offsets.size() == model_->num_dofs())
    return estimate_->offsets;
  return Eigen::VectorXd::Zero(model_->num_dofs());
}

void ReachController::evaluate(int frame) {
  if (true_poses_ == nullptr || true_poses_->poses.empty()) return;
  const Eigen::VectorXd& q = joint_state_->position;
  const Eigen::Isometry3d real = eye_hand_->palm_eye(true_poses_->poses);
  const Eigen::Isometry3d adapted = eye_hand_->palm_eye(q, adapted_offsets());
  const Eigen::Isometry3d nominal = eye_hand_->palm_eye(q, Eigen::VectorXd::Zero(q.size()));
  const Eigen::Isometry3d& desired = phase_->target_eye;
  using body_schema::orientation_error_deg;
  using body_schema::position_error_mm;
  FrameErrors e;
  e.estimation_mm = position_error_mm(real, adapted);
  e.estimation_deg = orientation_error_deg(real.linear(), adapted.linear());
  e.nominal_mm = position_error_mm(real, nominal);
  e.nominal_deg = orientation_error_deg(real.linear(), nominal.linear());
  e.reaching_mm = position_error_mm(desired, real);
  e.reaching_deg = orientation_error_deg(desired.linear(), real.linear());
  e.reaching_est_mm = position_error_mm(desired, adapted);
  e.reaching_est_deg = orientation_error_deg(desired.linear(), adapted.linear());
  report_->add(movement_id(movement_), frame, e);
}

void ReachController::begin_movement(int movement) {
  movement_ = movement;
  frame_ = 0;
  phase_->movement = movement;
  phase_->stage = ReachStage::kToStart;
  phase_->frame = 0;
  const MovementId id = movement_id(movement);
  phase_->target_eye = targets_[static_cast<std::size_t>(id.target)].pose_eye;
  from_ = joint_state_->position;
  goal_ = targets_[static_cast<std::size_t>(id.target)].starts[static_cast<std::size_t>(id.start)];
}

void ReachController::step(NodeContext& ctx) {
  if (targets_.front().posture.size() == 0) {  // first step: the encoders are known now
    plan_targets(ctx, joint_state_->position);
    begin_movement(0);
  } else if (movement_done_) {  // the last frame of a movement was observed at the last tick
    movement_done_ = false;
    begin_movement(movement_ + 1);
  } else if (phase_->stage == ReachStage::kOpenLoop && frame_ == open_frames_) {
    phase_->stage = ReachStage::kClosedLoop;
  }
  ++frame_;
  const Eigen::VectorXd& q = joint_state_->position;
  switch (phase_->stage) {
    case ReachStage::kToStart: {
      const double a = std::min(1.0, frame_ / (0.75 * to_start_frames_));
      command(from_ + a * (goal_ - from_));
      if (frame_ >= to_start_frames_) {
        phase_->stage = ReachStage::kOpenLoop;
        frame_ = 0;
        from_ = q;
        goal_ = targets_[static_cast<std::size_t>(movement_id(movement_).target)].posture;
      }
      break;
    }
    case ReachStage::kOpenLoop:
      command(from_ + (static_cast<double>(frame_) / open_frames_) * (goal_ - from_));
      break;
    case ReachStage::kClosedLoop:
      command(eye_hand_->servo_step(
          q, config_.adaptation ? adapted_offsets() : Eigen::VectorXd::Zero(q.size()),
          phase_->target_eye, config_.gain, ctx.period_s()));
      break;
    case ReachStage::kIdle:
      break;
  }
  if (phase_->stage != ReachStage::kOpenLoop && phase_->stage != ReachStage::kClosedLoop) return;
  // The phase keeps this frame's number and stage for this tick, so that the filter and the
  // reports running after this node observe frame 1 ... open + closed of every movement.
  phase_->frame = frame_;
  if (frame_ > 0) evaluate(frame_);
  if (frame_ == open_frames_ + closed_frames_) {
    ctx.report_progress(movement_ + 1, movements_, "movements");
    report_->movement_done();
    if (movement_ + 1 < movements_)
      movement_done_ = true;
    else
      ctx.request_stop(fmt::format("{} movements done", movements_));
  }
}

void ReachController::finish(NodeContext& ctx) {
  if (!report_) return;
  const nlohmann::json metrics = report_->metrics();
  for (const auto& [key, value] : metrics.items()) ctx.report_metric(key, value);
  if (!csv_name_.empty()) report_->write_csv(csv_path_);
  if (report_->movements_completed() > 0)
    report_->write_figures(
        ctx.figure_path("body_schema_estimation.png"), ctx.figure_path("body_schema_reaching.png"),
        ctx.figure_path("body_schema_closed_loop.png"), "node '" + ctx.node_name() + "'");
}

}  // namespace somasim::plugins
