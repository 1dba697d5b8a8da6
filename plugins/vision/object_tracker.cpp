#include "object_tracker.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "image_check.hpp"
#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/vision/stereo_object.hpp"

namespace somasim::plugins {
namespace {

constexpr int kMaxAreaRatio = 3;  // of the two eyes' object areas for one object

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
  v.block(kalman);
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
  model_ = robot::experiment_robot(ctx);
  eyes_believed_.configure(ctx, config_.eyes, model_);
  motion_.min_flow_px = config_.min_flow_px;
  motion_.min_area_px = config_.min_motion_px;
  compensate_ego_motion_ = config_.compensate_ego_motion;
  max_motion_fraction_ = config_.max_motion_fraction;
  still_frames_lost_ = config_.still_frames_lost;
  still_px_ = config_.still_px;
  vision::ColourTrackerOptions colour;
  colour.min_saturation = config_.min_saturation;
  colour.min_value = config_.min_value;
  colour.min_object_px = config_.min_object_px;
  colour.lost_fraction = config_.lost_fraction;
  colour.max_background_ratio = config_.max_background_ratio;
  if (config_.refuse_own_colours) colour.own_colours = rendered_colours(*model_);
  for (Eye& eye : eyes_) eye.tracker = vision::ColourTracker(colour);
  max_reprojection_px_ = config_.max_reprojection_px;
  inconsistent_frames_lost_ = config_.inconsistent_frames_lost;
  unfixed_frames_lost_ = config_.unfixed_frames_lost;
  max_distance_ = config_.max_distance_m;
  max_jump_ = config_.max_jump_m;
  max_colour_distance_ = config_.max_colour_distance;
  reset_after_lost_ = config_.reset_after_lost;
  predict_windows_ = config_.predict_windows;
  radius_min_ = config_.radius_min;
  radius_max_ = config_.radius_max;
  if (radius_max_ < radius_min_)
    config_error(ctx, config_, config_.radius_max,
                 fmt::format("{} is below radius_min {}", radius_max_, radius_min_));
  kalman_ = vision::KalmanTracker(config_.kalman);

  left_ = &ports_.eyes.left_eye_rgb.get();
  right_ = &ports_.eyes.right_eye_rgb.get();
  joints_ = &ports_.eyes.joint_state.get();
  truth_ = ports_.truth.get();
  stimulus_ = &ports_.stimulus.get();
  pixels_ = &ports_.object_pixels.get();
}

void ObjectTracker::track_eye(Eye& eye, const Image& image, const render::Camera& camera,
                              double dt_s) {
  const auto& k = camera.intrinsics;
  const cv::Matx33d ego =
      compensate_ego_motion_ && !eye.previous.empty()
          ? vision::rotation_homography(eye.previous_rotation, camera.pose_root.linear(), k.fx,
                                        k.fy, k.cx, k.cy)
          : cv::Matx33d::eye();
  if (eye.tracker.tracking()) {
    cv::Matx33d shift = ego;  // the head's own turn
    if (predict_windows_ && kalman_.initialised() && lost_ < reset_after_lost_ && dt_s > 0)
      shift = vision::predicted_image_shift(camera, kalman_.position(), kalman_.velocity(),
                                            dt_s) *
              ego;  // and the object's own motion
    eye.tracker.shift_window(shift);
  }
  eye.track = eye.tracker.tracking() ? eye.tracker.track(image.data) : vision::ColourTrack{};
  if (!eye.track.tracked && !eye.tracker.tracking() && eye.track.window.area() > 0) ++losses_;
  if (eye.track.tracked) {
    // Motion consistency: a static thing of the object's colour is not the object.
    const cv::Vec3d a = ego * cv::Vec3d(eye.anchor_px.x(), eye.anchor_px.y(), 1.0);
    const Eigen::Vector2d anchor(a[0] / a[2], a[1] / a[2]);
    if ((eye.track.centre_px - anchor).norm() > still_px_ ||
        std::abs(eye.track.radius_px - eye.anchor_radius_px) > still_px_) {
      eye.anchor_px = eye.track.centre_px;
      eye.anchor_radius_px = eye.track.radius_px;
      eye.still_frames = 0;
    } else if (++eye.still_frames >= still_frames_lost_) {
      eye.tracker.lose();
      eye.track.tracked = false;
      ++still_drops_;
    } else {
      eye.anchor_px = anchor;
    }
  }
  if (!eye.track.tracked && !eye.previous.empty()) {
    const vision::MotionBlob m = vision::detect_motion(eye.previous, image.data, motion_, ego);
    const double image_px = static_cast<double>(image.data.total());
    if (m.found && m.area_px <= max_motion_fraction_ * image_px) {
      if (eye.tracker.acquire(image.data, m.mask)) {
        ++acquisitions_;
        eye.track = eye.tracker.track(image.data);
        eye.anchor_px = eye.track.centre_px;
        eye.anchor_radius_px = eye.track.radius_px;
        eye.still_frames = 0;
      } else {
        ++refused_;
        if (eye.tracker.last_refusal() == vision::Refusal::kOwnColour) ++own_colour_refused_;
      }
    } else if (m.found) {
      ++refused_;
    }
  }
  image.data.copyTo(eye.previous);
  eye.previous_rotation = camera.pose_root.linear();
}

void ObjectTracker::drop_unfixed(bool fixed) {
  for (Eye& eye : eyes_) {
    eye.unfixed_frames = fixed || !eye.tracker.tracking() ? 0 : eye.unfixed_frames + 1;
    if (eye.unfixed_frames >= unfixed_frames_lost_) {
      eye.tracker.lose();
      eye.unfixed_frames = 0;
      ++unfixed_drops_;
    }
  }
}

void ObjectTracker::lose(double dt_s) {
  stimulus_->present = false;
  ++lost_;
  if (lost_ >= reset_after_lost_)
    kalman_.reset();
  else if (dt_s > 0)
    kalman_.predict(dt_s);
  stimulus_->position = kalman_.position();
  stimulus_->velocity = kalman_.velocity();
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
  ++frames_;

  // The cameras where the believed head and eye kinematics put them when the images were
  // rendered (the head may be moving).
  const std::vector<render::Camera> cams = eyes_believed_.pose(joints_at(left_->time_s));
  track_eye(eyes_[0], *left_, cams[0], dt);
  track_eye(eyes_[1], *right_, cams[1], dt);

  const auto pixels = [](const vision::ColourTrack& t) {
    if (!t.tracked) return StereoPixels::Eye{};
    return StereoPixels::Eye{true, t.centre_px, t.centre_px, t.object_px};
  };
  pixels_->left = pixels(eyes_[0].track);
  pixels_->right = pixels(eyes_[1].track);
  pixels_->frame = left_->frame;

  const vision::ColourTrack& l = eyes_[0].track;
  const vision::ColourTrack& r = eyes_[1].track;
  vision::StereoObject object;
  // A track cut by the image border has an unknown centre; two tracks of very different areas
  // are not the same object (or one of them is mostly hidden): no fix, but no loss either.
  const auto at_border = [](const vision::ColourTrack& t, const Image& image) {
    const Eigen::Vector2d& c = t.centre_px;
    return c.x() - t.radius_px < 1 || c.y() - t.radius_px < 1 ||
           c.x() + t.radius_px > image.data.cols - 2 || c.y() + t.radius_px > image.data.rows - 2;
  };
  const bool comparable =
      l.tracked && r.tracked &&
      std::max(l.object_px, r.object_px) <= kMaxAreaRatio * std::min(l.object_px, r.object_px);
  const bool border = l.tracked && r.tracked && (at_border(l, *left_) || at_border(r, *right_));
  if (l.tracked && r.tracked && (border || !comparable)) {
    ++partial_;
    partial_border_ += border ? 1 : 0;
    // Unlike areas, neither cut by the border: one eye holds something else (e.g. clutter
    // its tracker slid onto when the last object went). The smaller track is dropped and its
    // eye re-acquires by motion; the object, if that was it, is moving and is found again.
    if (!border) {
      eyes_[l.object_px < r.object_px ? 0 : 1].tracker.lose();
      ++area_drops_;
    }
  } else if (l.tracked && r.tracked) {
    object = vision::triangulate_object(cams[0], l.centre_px, l.radius_px, cams[1], r.centre_px,
                                        r.radius_px);
    const bool same_colours =
        vision::colour_distance(eyes_[0].tracker, eyes_[1].tracker) <= max_colour_distance_;
    if (!same_colours) ++colour_mismatches_;
    if (!object.centre.valid || object.centre.reprojection_error_px > max_reprojection_px_ ||
        !same_colours) {
      object.centre.valid = false;
      if (++inconsistent_ >= inconsistent_frames_lost_) {  // re-acquire both by motion
        for (Eye& eye : eyes_) eye.tracker.lose();
        ++inconsistent_drops_;
        inconsistent_ = 0;
      }
    } else if ((object.centre.point -
                0.5 * (cams[0].pose_root.translation() + cams[1].pose_root.translation()))
                   .norm() > max_distance_) {
      object.centre.valid = false;  // the backdrop, not an object near the body
      for (Eye& eye : eyes_) eye.tracker.lose();
      ++far_drops_;
      inconsistent_ = 0;
    } else if (lost_ == 0 && kalman_.initialised() && dt > 0.0 &&
               (object.centre.point - (kalman_.position() + dt * kalman_.velocity())).norm() >
                   max_jump_) {
      object.centre.valid = false;  // not the object of the previous frame
      for (Eye& eye : eyes_) eye.tracker.lose();
      ++jump_drops_;
      inconsistent_ = 0;
    } else {
      inconsistent_ = 0;
    }
  }
  drop_unfixed(object.centre.valid);
  if (!object.centre.valid) {
    pixels_->left.found = pixels_->right.found = false;
    lose(dt);
  } else {
    if (dt <= 0.0 || lost_ >= reset_after_lost_) kalman_.reset();
    kalman_.update(object.centre.point, dt > 0.0 ? dt : ctx.period_s());
    lost_ = 0;
    ++tracked_;
    reprojection_sum_ += object.centre.reprojection_error_px;
    stimulus_->present = true;
    stimulus_->position = kalman_.position();
    stimulus_->velocity = kalman_.velocity();
    stimulus_->radius = std::clamp(object.radius_m, radius_min_, radius_max_);
  }
  if (truth_) score_against_truth(cams);
}

void ObjectTracker::score_against_truth(const std::vector<render::Camera>& cameras) {
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
  ctx.report_metric("frames", frames_);
  ctx.report_metric("frames_tracked", tracked_);
  ctx.report_metric("tracked_share", share(tracked_, frames_));
  ctx.report_metric("acquisitions", acquisitions_);
  ctx.report_metric("losses", losses_);
  ctx.report_metric("inconsistent_drops", inconsistent_drops_);
  ctx.report_metric("unfixed_drops", unfixed_drops_);
  ctx.report_metric("area_drops", area_drops_);
  ctx.report_metric("partial_frames", partial_);
  ctx.report_metric("partial_border_frames", partial_border_);
  ctx.report_metric("still_drops", still_drops_);
  ctx.report_metric("far_drops", far_drops_);
  ctx.report_metric("jump_drops", jump_drops_);
  ctx.report_metric("colour_mismatches", colour_mismatches_);
  ctx.report_metric("refused_acquisitions", refused_);
  ctx.report_metric("own_colour_refusals", own_colour_refused_);
  ctx.report_metric("pose_time_offset_max_s", pose_time_offset_max_s_);
  ctx.report_metric("reprojection_mean_px",
                    tracked_ ? reprojection_sum_ / static_cast<double>(tracked_) : 0.0);
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
