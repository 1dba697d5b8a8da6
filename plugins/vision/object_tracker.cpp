#include "object_tracker.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "image_check.hpp"
#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"

namespace somasim::plugins {
namespace {

bool inside(const render::Camera& c, const Eigen::Vector3d& p) {
  const auto uv = c.project(p);
  return uv && uv->x() >= 0 && uv->y() >= 0 && uv->x() <= c.intrinsics.width - 1 &&
         uv->y() <= c.intrinsics.height - 1;
}

cv::Vec3b rgb8(const Eigen::Vector3f& c) {
  const auto u8 = [](float v) {
    return static_cast<unsigned char>(std::lround(255.0F * std::clamp(v, 0.0F, 1.0F)));
  };
  return {u8(c.x()), u8(c.y()), u8(c.z())};
}

// Every colour the camera renders the robot in: each link's colour and its coloured visuals.
std::vector<cv::Vec3b> rendered_colours(const robot::RobotModel& model) {
  std::vector<cv::Vec3b> out;
  for (int i = 0; i < model.num_links(); ++i) {
    const robot::Link& link = model.link(i);
    out.push_back(rgb8(render::link_colour(link.name)));
    for (const robot::Geometry& g : link.visual)
      if (g.colour) out.push_back(rgb8(g.colour->cast<float>()));
  }
  return out;
}

}  // namespace

const vision::StereoTrackerOptions& ObjectTracker::Config::defaults() {
  static const vision::StereoTrackerOptions options;
  return options;
}

template <class V>
void ObjectTracker::Config::visit(V& v) {
  v.block(robot);
  v.block(eyes);
  v.field("min_flow_px", min_flow_px)
      .unit("px")
      .range(0.01, 100)
      .doc("optical-flow magnitude per frame that counts as motion");
  v.field("min_motion_px", min_motion_px)
      .at_least(1)
      .doc("smallest moving blob [px] that acquires an object");
  v.field("max_motion_fraction", max_motion_fraction)
      .range(0.001, 1.0)
      .doc(
          "a moving blob larger than this fraction of the image acquires nothing (the whole "
          "scene jumped, e.g. the first posture or an uncompensated head turn)");
  v.field("still_frames_lost", still_frames_lost)
      .at_least(1)
      .doc(
          "a track that has not moved by still_px (centre or radius, beyond the camera's own "
          "rotation) for this many frames is dropped: the moving object was lost and the "
          "colour tracker locked on to static clutter of its colour");
  v.field("still_px", still_px)
      .unit("px")
      .at_least(0.01)
      .doc("how far a track must move to count as moving (see still_frames_lost)");
  v.field("max_background_ratio", max_background_ratio)
      .at_least(0.01)
      .doc(
          "an acquisition is refused when the acquired colours cover more pixels elsewhere in "
          "the image than on the moving blob, times this (colours of the backdrop or robot)");
  v.field("refuse_own_colours", refuse_own_colours)
      .doc(
          "refuse acquisitions whose colour mode is one of the robot's own rendered colours "
          "(its links' and coloured visuals', from the robot model): the robot's own moving "
          "hand is not an object (metric own_colour_refusals)");
  v.field("compensate_ego_motion", compensate_ego_motion)
      .doc(
          "warp the previous image by the rotation of the (believed) camera between the frames "
          "before the flow, so that a turning head is not taken for a moving object");
  v.field("min_saturation", min_saturation)
      .range(0, 255)
      .doc("pixels less saturated carry no colour (OpenCV HSV, 0-255)");
  v.field("min_value", min_value)
      .range(0, 255)
      .doc("darker pixels carry no colour (OpenCV HSV, 0-255)");
  v.field("min_object_px", min_object_px)
      .at_least(1)
      .doc("fewest object pixels for an acquisition or a tracked image");
  v.field("lost_fraction", lost_fraction)
      .range(0.01, 0.99)
      .doc(
          "a track is lost when its object pixels fall below this fraction of their running "
          "mean (the back-projection mass collapsed)");
  v.field("max_reprojection_px", max_reprojection_px)
      .unit("px")
      .at_least(0.01)
      .doc(
          "a triangulation whose RMS reprojection error exceeds this is no fix (the eyes track "
          "different things)");
  v.field("max_jump_m", max_jump_m)
      .unit("m")
      .range(0.001, 100)
      .doc(
          "a fix farther than this from where the Kalman filter predicts the object tracked in "
          "the previous frame is something else the colour trackers slid onto (the object was "
          "removed or hidden): both are dropped and re-acquired by motion (metric jump_drops)");
  v.field("jump_check_after_missed", jump_check_after_missed)
      .doc(
          "apply max_jump_m also to the first fix after frames without one, against the "
          "filter's prediction carried through them (while it still predicts: fewer than "
          "reset_after_lost frames): the fix of something else the eyes found in the gap is not "
          "joined to the track of the object they lost; false = only consecutive fixes are "
          "checked");
  v.field("max_distance_m", max_distance_m)
      .unit("m")
      .range(0.05, 100.0)
      .doc(
          "a triangulated object farther than this from the middle of the two eyes is no fix and "
          "both tracks are dropped (metric far_drops): the peripersonal space is near, and a "
          "distant piece of the backdrop taken for an object while the head turned (parallax) "
          "would otherwise hold the gaze");
  v.field("max_colour_distance", max_colour_distance)
      .range(0.0, 1.0)
      .doc(
          "the two eyes' colour models (Bhattacharyya distance of their hue-saturation "
          "histograms, 0 = the same, 1 = disjoint) must be closer than this for a fix; farther "
          "apart, the eyes follow different things and the frame counts as inconsistent");
  v.field("max_size_ratio", max_size_ratio)
      .range(0.0, 100.0)
      .doc(
          "the two eyes' object radii, each scaled to the triangulated depth (radius px x depth / "
          "focal length), may differ by at most this ratio (larger over smaller) for a fix; "
          "beyond it the eyes hold two different things whose rays happen to meet (e.g. one eye a "
          "patch of backdrop of the object's colour) and the frame counts as inconsistent "
          "(metric size_mismatches; outcome unlike_sizes); 0 = no check");
  v.field("inconsistent_frames_lost", inconsistent_frames_lost)
      .at_least(1)
      .doc(
          "after this many consecutive frames whose two tracks do not triangulate, both tracks "
          "are dropped and the object re-acquired by motion");
  v.field("unfixed_frames_lost", unfixed_frames_lost)
      .at_least(1)
      .doc(
          "an eye's track that gave no stereo fix for this many consecutive frames (the other "
          "eye sees nothing, or something unlike it, or it is cut by the border) is dropped "
          "and the eye re-acquires by motion: a track left on clutter when the object went "
          "cannot keep the eye from acquiring the next object (metric unfixed_drops)");
  v.field("reset_after_lost", reset_after_lost)
      .at_least(1)
      .doc("frames without a fix after which the Kalman filter starts afresh");
  v.field("radius_min", radius_min)
      .unit("m")
      .range(1e-4, 1.0)
      .doc("the output radius (from area and depth) is clamped to [radius_min, radius_max]");
  v.field("radius_max", radius_max)
      .unit("m")
      .range(1e-4, 10.0)
      .doc("upper clamp of the output radius");
  v.field("predict_windows", predict_windows)
      .doc(
          "before each CamShift step, move each eye's search window by the image motion the "
          "Kalman filter predicts for the object (its velocity over the frame interval, "
          "projected): an object that moves farther in a frame than its window is wide (about "
          "1 m/s at 0.45 m and 20 Hz for a 1.2 cm ball) is met instead of lost");
  v.field("max_velocity_sigma", max_velocity_sigma)
      .unit("m/s")
      .at_least(0.0)
      .doc(
          "a fix whose velocity the Kalman filter does not yet know to this σ (its first fixes "
          "after an acquisition: about 0.15 m/s at the second, 0.1 m/s at the fifth with the "
          "defaults) is reported with velocity 0, so that no time to contact is read from the "
          "difference of two noisy positions (metric velocity_withheld_frames); 0 = the "
          "velocity is always reported");
  v.field("velocity_window_fixes", velocity_window_fixes)
      .at_least(2)
      .doc(
          "the track's last fixes a straight line is fitted to, for max_velocity_disagreement "
          "and max_radius_rate");
  v.field("max_velocity_disagreement", max_velocity_disagreement)
      .unit("m/s")
      .at_least(0.0)
      .doc(
          "a fix whose filtered velocity differs by more than this from the slope of the "
          "least-squares line through the track's last velocity_window_fixes fixes (or whose "
          "track has fewer fixes) is reported with velocity 0: the filter's velocity is read "
          "only where the track's own positions show it, not from a transient of its "
          "acceleration state (metrics velocity_withheld_frames, velocity_disputed_frames); 0 = "
          "no check");
  v.field("max_radius_rate", max_radius_rate)
      .unit("1/s")
      .at_least(0.0)
      .doc(
          "a track's radius (from area and depth) that changes faster than this fraction of "
          "itself per second over its last velocity_window_fixes fixes (the least-squares slope, "
          "from three fixes on) is still settling: that fix and the next velocity_window_fixes - "
          "1 are reported with velocity 0 (so are a new track's first, too few for the window). "
          "A rigid object keeps its size: a radius growing or shrinking is a window still "
          "settling onto its object, or two eyes whose windows hold different things, and the "
          "motion its fixes show is the windows', which the filter's velocity remembers for a "
          "while (metrics velocity_withheld_frames, radius_unsettled_frames); 0 = no check");
  v.field("velocity_over_settling", velocity_over_settling)
      .at_least(0.0)
      .doc(
          "a fix's velocity is reported only where its speed exceeds this multiple of the speed "
          "at which the track's radius changes (the least-squares slope of its last "
          "velocity_window_fixes radii, m/s): a window that grows or shrinks by dR moves its "
          "centre up to dR across the image and the triangulated depth up to depth / baseline "
          "times that (about 6 at 0.4 m with the iCub's 6.8 cm), so a smaller velocity is the "
          "window's own, not the object's (metrics velocity_withheld_frames, "
          "velocity_settling_frames); 0 = no check");
  v.block(kalman);
  v.field("trace", trace)
      .doc(
          "a CSV written into the run folder, one row per stereo frame: each eye's track, the "
          "fix or the check that refused the frame (outcome: fixed, no_track, left_only, "
          "right_only, border, unlike_areas, not_triangulated, colour_mismatch, unlike_sizes, "
          "too_far, jump), the filter's position and velocity, whether the velocity was "
          "reported, and the truth where it is wired; '' = none");
}

void ObjectTracker::Config::validate(ConfigChecks& checks) const {
  checks.require(radius_max >= radius_min, radius_max,
                 fmt::format("{} is below radius_min {}", radius_max, radius_min));
}

template <class V>
void ObjectTracker::Ports::visit(V& v) {
  v.block(eyes);
  v.port("truth", truth,
         "optional ground truth (e.g. object_thrower.truth): metrics position_rms_m, "
         "velocity_rms_m_s, latency_s, tracked shares");
  v.port("stimulus", stimulus,
         "the object in the root frame: Kalman position [m] and velocity [m/s], radius from the "
         "tracked area and depth [m]; present only in frames with a triangulated fix");
  v.port("object_pixels", object_pixels,
         "the tracked object in each image: found, centre (u, v) [px], area "
         "[px] (somasim/vision/ports.hpp)");
}

PluginSpec ObjectTracker::spec() {
  return make_plugin_spec<Config, Ports>(
      "object_tracker",
      "A moving object seen by two eyes (the PPS study's Fig 13 pipeline): motion detection by "
      "dense optical flow acquires it in each image, a CamShift tracker of its hue-saturation "
      "histogram follows it, the two image centres are triangulated through the believed "
      "head/eye kinematics (encoders + joint_offsets_deg) into the root frame, its radius comes "
      "from the tracked area and the depth, and a Kalman filter gives position and velocity. A "
      "track whose colour collapses (the object left, was removed or hidden) is lost and the "
      "object re-acquired by motion. With a wired truth: tracking errors, latency and the share "
      "of frames tracked.");
}

void ObjectTracker::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  eyes_believed_.configure(ctx, config_.eyes, model_);
  vision::StereoTrackerOptions options;
  options.motion.min_flow_px = config_.min_flow_px;
  options.motion.min_area_px = config_.min_motion_px;
  options.colour.min_saturation = config_.min_saturation;
  options.colour.min_value = config_.min_value;
  options.colour.min_object_px = config_.min_object_px;
  options.colour.lost_fraction = config_.lost_fraction;
  options.colour.max_background_ratio = config_.max_background_ratio;
  if (config_.refuse_own_colours) options.colour.own_colours = rendered_colours(*model_);
  options.max_motion_fraction = config_.max_motion_fraction;
  options.compensate_ego_motion = config_.compensate_ego_motion;
  options.still_frames_lost = config_.still_frames_lost;
  options.still_px = config_.still_px;
  options.max_reprojection_px = config_.max_reprojection_px;
  options.max_jump_m = config_.max_jump_m;
  options.jump_check_after_missed = config_.jump_check_after_missed;
  options.max_distance_m = config_.max_distance_m;
  options.max_colour_distance = config_.max_colour_distance;
  options.max_size_ratio = config_.max_size_ratio;
  options.inconsistent_frames_lost = config_.inconsistent_frames_lost;
  options.unfixed_frames_lost = config_.unfixed_frames_lost;
  options.reset_after_lost = config_.reset_after_lost;
  options.predict_windows = config_.predict_windows;
  options.velocity_window_fixes = config_.velocity_window_fixes;
  options.kalman = config_.kalman;
  tracker_ = vision::StereoObjectTracker(options);
  if (config_.max_radius_rate > 0.0)
    settling_.emplace(config_.max_radius_rate, config_.velocity_window_fixes);
  if (config_.trace.enabled()) trace_.emplace();

  left_ = &ports_.eyes.left_eye_rgb.get();
  right_ = &ports_.eyes.right_eye_rgb.get();
  joints_ = &ports_.eyes.joint_state.get();
  truth_ = ports_.truth.get();
  stimulus_ = &ports_.stimulus.get();
  pixels_ = &ports_.object_pixels.get();
}

const Eigen::VectorXd& ObjectTracker::joints_at(double time_s) {
  const auto best = std::min_element(
      joint_history_.begin(), joint_history_.end(), [&](const auto& a, const auto& b) {
        return std::abs(a.first - time_s) < std::abs(b.first - time_s);
      });
  pose_time_offset_max_s_ = std::max(pose_time_offset_max_s_, std::abs(best->first - time_s));
  return best->second;
}

void ObjectTracker::step(NodeContext& ctx) {
  if (joints_->position.size() > 0 &&
      (joint_history_.empty() || joint_history_.back().first < ctx.time_s())) {
    joint_history_.emplace_back(ctx.time_s(), joints_->position);
    while (joint_history_.size() > 2 && joint_history_.front().first < ctx.time_s() - 1.0)
      joint_history_.pop_front();
  }
  if (left_->data.empty() || right_->data.empty() || joints_->position.size() == 0) {
    stimulus_->present = false;
    return;
  }
  if (left_->frame == last_frame_) return;  // no new image: the outputs hold
  check_camera_image(*model_, *left_, "left_eye_rgb", eyes_believed_.names()[0]);
  check_camera_image(*model_, *right_, "right_eye_rgb", eyes_believed_.names()[1]);
  if (joints_->position.size() != model_->num_dofs())
    throw RunError(fmt::format("input 'joint_state': expected {} joint values (robot '{}'), got {}",
                               model_->num_dofs(), model_->name(), joints_->position.size()));
  const double dt = last_frame_ == 0 ? 0.0 : left_->time_s - last_time_s_;
  last_frame_ = left_->frame;
  last_time_s_ = left_->time_s;

  // The cameras where the believed head and eye kinematics put them when the images were
  // rendered (the head may be moving).
  const std::vector<render::Camera> posed = eyes_believed_.pose(joints_at(left_->time_s));
  const std::array<render::Camera, 2> cams{posed[0], posed[1]};
  const vision::StereoFix fix =
      tracker_.update(left_->data, right_->data, cams, dt, ctx.period_s());

  const auto pixels = [&](const vision::ColourTrack& t) {
    if (!t.tracked) return StereoPixels::Eye{};
    return StereoPixels::Eye{fix.fixed, t.centre_px, t.centre_px, t.object_px};
  };
  pixels_->left = pixels(fix.tracks[0]);
  pixels_->right = pixels(fix.tracks[1]);
  pixels_->frame = left_->frame;
  stimulus_->present = fix.fixed;
  stimulus_->position = fix.position;
  stimulus_->velocity = fix.velocity;
  const bool velocity_reported = fix.fixed && velocity_is_known(fix);
  if (fix.fixed && !velocity_reported) {
    stimulus_->velocity.setZero();
    ++velocity_withheld_frames_;
  }
  if (trace_) trace_->add(left_->time_s, fix, velocity_reported, truth_);
  if (fix.fixed)
    stimulus_->radius = std::clamp(fix.radius_m, config_.radius_min, config_.radius_max);
  if (truth_) score_against_truth(cams);
}

bool ObjectTracker::velocity_is_known(const vision::StereoFix& fix) {
  // The settling gate sees every fix of a track, whatever the checks before it decide.
  const bool settled = !settling_ || settling_->update(fix.window_fixes, fix.window_radius_rate);
  if (config_.max_velocity_sigma > 0.0 && fix.velocity_sigma > config_.max_velocity_sigma)
    return false;
  if (!settled) {
    ++radius_unsettled_frames_;
    return false;
  }
  // How fast the track's radius changes [m/s]: its window's own motion is at most a few times that.
  const double settling_speed = fix.window_radius_rate * fix.radius_m;
  if (config_.velocity_over_settling > 0.0 &&
      fix.velocity.norm() < config_.velocity_over_settling * settling_speed) {
    ++velocity_settling_frames_;
    return false;
  }
  if (config_.max_velocity_disagreement <= 0.0) return true;
  if (fix.window_fixes >= config_.velocity_window_fixes &&
      (fix.velocity - fix.window_velocity).norm() <= config_.max_velocity_disagreement)
    return true;
  ++velocity_disputed_frames_;
  return false;
}

void ObjectTracker::score_against_truth(const std::array<render::Camera, 2>& cameras) {
  if (!truth_->present) {
    if (stimulus_->present) ++false_fixes_;
    return;
  }
  ++truth_frames_;
  const bool in_view = inside(cameras[0], truth_->position) && inside(cameras[1], truth_->position);
  in_view_ += in_view ? 1 : 0;
  if (!stimulus_->present) return;
  ++truth_tracked_;
  in_view_tracked_ += in_view ? 1 : 0;
  const Eigen::Vector3d e = stimulus_->position - truth_->position;
  position_sq_sum_ += e.squaredNorm();
  velocity_sq_sum_ += (stimulus_->velocity - truth_->velocity).squaredNorm();
  ++error_count_;
  lag_.add(e, truth_->velocity);
}

void ObjectTracker::finish(NodeContext& ctx) {
  const auto share = [](std::int64_t n, std::int64_t of) {
    return of ? static_cast<double>(n) / static_cast<double>(of) : 0.0;
  };
  const vision::StereoTrackerCounts& n = tracker_.counts();
  ctx.report_metric("frames", n.frames);
  ctx.report_metric("frames_tracked", n.fixes);
  ctx.report_metric("tracked_share", share(n.fixes, n.frames));
  ctx.report_metric("acquisitions", n.acquisitions);
  ctx.report_metric("losses", n.losses);
  ctx.report_metric("inconsistent_drops", n.inconsistent_drops);
  ctx.report_metric("unfixed_drops", n.unfixed_drops);
  ctx.report_metric("area_drops", n.area_drops);
  ctx.report_metric("partial_frames", n.partial);
  ctx.report_metric("partial_border_frames", n.partial_border);
  ctx.report_metric("still_drops", n.still_drops);
  ctx.report_metric("far_drops", n.far_drops);
  ctx.report_metric("jump_drops", n.jump_drops);
  ctx.report_metric("colour_mismatches", n.colour_mismatches);
  ctx.report_metric("size_mismatches", n.size_mismatches);
  ctx.report_metric("refused_acquisitions", n.refused);
  ctx.report_metric("own_colour_refusals", n.own_colour_refused);
  ctx.report_metric("pose_time_offset_max_s", pose_time_offset_max_s_);
  ctx.report_metric("velocity_withheld_frames", velocity_withheld_frames_);
  ctx.report_metric("velocity_disputed_frames", velocity_disputed_frames_);
  ctx.report_metric("radius_unsettled_frames", radius_unsettled_frames_);
  ctx.report_metric("velocity_settling_frames", velocity_settling_frames_);
  ctx.report_metric("reprojection_mean_px",
                    n.fixes ? n.reprojection_sum_px / static_cast<double>(n.fixes) : 0.0);
  if (trace_) trace_->write(config_.trace.path);
  if (!truth_) return;
  ctx.report_metric("frames_with_object", truth_frames_);
  ctx.report_metric("object_tracked_share", share(truth_tracked_, truth_frames_));
  ctx.report_metric("frames_in_view", in_view_);
  ctx.report_metric("in_view_tracked_share", share(in_view_tracked_, in_view_));
  ctx.report_metric("false_fixes", false_fixes_);
  const auto rms = [&](double sum) {
    return error_count_ ? std::sqrt(sum / static_cast<double>(error_count_)) : 0.0;
  };
  ctx.report_metric("position_rms_m", rms(position_sq_sum_));
  ctx.report_metric("velocity_rms_m_s", rms(velocity_sq_sum_));
  ctx.report_metric("latency_s", lag_.seconds());
}

}  // namespace somasim::plugins
