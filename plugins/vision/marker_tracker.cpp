#include "marker_tracker.hpp"

#include "image_check.hpp"

#include <cmath>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/vision/stereo.hpp"

namespace somasim::plugins {
namespace {

std::string hsv_text(const cv::Vec3b& v) {
  return fmt::format("[{}, {}, {}]", v[0], v[1], v[2]);
}

}  // namespace

template <class V>
void MarkerTracker::Config::visit(V& v) {
  v.block(robot);
  v.block(eyes);
  v.field("hsv_low", hsv_low)
      .size(3)
      .range(0, 255)
      .doc(
          "lower HSV bound of the marker's colour (OpenCV: H 0-179, S and V 0-255; default "
          "green); H above hsv_high's H wraps around 180 (red)");
  v.field("hsv_high", hsv_high).size(3).range(0, 255).doc("upper HSV bound");
  v.field("min_area_px", min_area_px)
      .at_least(1)
      .doc("smallest blob [px] taken for the marker in an image");
  v.field("marker_radius", marker_radius)
      .unit("m")
      .range(1e-4, 1.0)
      .doc("radius of the output stimulus [m] (the marker sphere of the robot description)");
  v.field("marker_frame", marker_frame)
      .doc(
          "frame (or link) of the robot model at the marker: where the believed kinematics "
          "expect it, to tell a wrong colour range from a hidden marker");
  v.field("max_distance_from_believed", max_distance_from_believed)
      .unit("m")
      .range(0.0, 10.0)
      .doc(
          "a triangulated blob pair farther than this from where the believed kinematics "
          "(encoders + joint_offsets_deg) put marker_frame is not the marker - e.g. two blobs "
          "of unlike parts of a half-hidden marker matched at a wrong depth, or something else "
          "of its colour (metric far_from_believed_rejections); 0 = no such check. Give "
          "joint_offsets_deg the robot's believed arm offsets too, so that the check uses what "
          "the robot believes, not the true arm");
  v.field("blob_centre", blob_centre)
      .doc(
          "the marker's pixel position in an image: the centre of the blob's enclosing circle "
          "(right for a round marker up to half hidden, e.g. behind its finger) or the blob's "
          "centroid");
  v.field("max_reprojection_px", max_reprojection_px)
      .unit("px")
      .at_least(0.01)
      .doc(
          "a triangulation whose RMS reprojection error exceeds this is rejected (the eyes saw "
          "different blobs)");
  v.field("no_colour_frames_error", no_colour_frames_error)
      .at_least(0)
      .doc(
          "run error after this many consecutive frames with no pixel in the colour range in "
          "either image while the marker is believed in view of both eyes; 0 = never");
  v.field("reset_after_lost", reset_after_lost)
      .at_least(1)
      .doc("frames without a fix after which the Kalman filter starts afresh");
  v.block(kalman);
}

template <class V>
void MarkerTracker::Ports::visit(V& v) {
  v.block(eyes);
  v.port("true_link_poses", true_link_poses,
         "optional ground truth (e.g. world.link_poses): the true marker_frame gives "
         "the metrics position_rms_m and velocity_rms_m_s");
  v.port("stimulus", stimulus,
         "the marker in the root frame: Kalman position [m] and velocity [m/s], radius "
         "marker_radius; present only in frames with a triangulated fix");
  v.port("marker_pixels", marker_pixels,
         "the marker's blob in each image: found, centroid (u, v) [px], area "
         "[px] (somasim/vision/ports.hpp)");
}

PluginSpec MarkerTracker::spec() {
  return make_plugin_spec<Config, Ports>(
      "marker_tracker",
      "A coloured marker (default: the iCub's green right index fingertip) seen by two eyes: the "
      "largest blob in an HSV range in each image, stereo triangulation through the believed "
      "head/eye kinematics (encoders + joint_offsets_deg) into the root frame, and a Kalman "
      "filter for position and velocity. A colour range that matches no pixel of either image "
      "while the believed kinematics put the marker in view of both eyes for "
      "no_colour_frames_error frames is a run error; a marker that is hidden or too small is "
      "reported as present = false (metric tracked_share).");
}

void MarkerTracker::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  eyes_believed_.configure(ctx, config_.eyes, model_);
  const auto low = config_.hsv_low;
  const auto high = config_.hsv_high;
  if (low[0] > 179)
    config_error(ctx, config_, config_.hsv_low,
                 fmt::format("hue {} is above 179 (OpenCV's hue is degrees / 2)", low[0]));
  if (high[0] > 179)
    config_error(ctx, config_, config_.hsv_high,
                 fmt::format("hue {} is above 179 (OpenCV's hue is degrees / 2)", high[0]));
  for (int i = 0; i < 3; ++i) {
    range_.low[i] = static_cast<unsigned char>(std::lround(low[static_cast<std::size_t>(i)]));
    range_.high[i] = static_cast<unsigned char>(std::lround(high[static_cast<std::size_t>(i)]));
  }
  for (int i = 1; i < 3; ++i)
    if (range_.low[i] > range_.high[i])
      config_error(ctx, config_, config_.hsv_low,
                   fmt::format("{} {} is above hsv_high's {}", i == 1 ? "saturation" : "value",
                               range_.low[i], range_.high[i]));
  range_text_ =
      fmt::format("hsv_low {} .. hsv_high {}", hsv_text(range_.low), hsv_text(range_.high));
  use_circle_ = config_.blob_centre == BlobCentre::kCircle;
  const std::string marker_frame = config_.marker_frame;
  if (model_->find_frame(marker_frame) < 0 && model_->find_link(marker_frame) < 0)
    config_error(ctx, config_, config_.marker_frame,
                 fmt::format("'{}' is neither a frame nor a link of robot '{}'", marker_frame,
                             model_->name()));
  marker_ref_ = model_->frame_ref(marker_frame);
  kalman_ = vision::KalmanTracker(config_.kalman);

  left_ = &ports_.eyes.left_eye_rgb.get();
  right_ = &ports_.eyes.right_eye_rgb.get();
  joints_ = &ports_.eyes.joint_state.get();
  truth_ = ports_.true_link_poses.get();
  stimulus_ = &ports_.stimulus.get();
  pixels_ = &ports_.marker_pixels.get();
  stimulus_->radius = config_.marker_radius;
}

bool MarkerTracker::looks_like_marker(const render::Camera& camera, const vision::MarkerBlob& blob,
                                      const Eigen::Vector3d& point_root) const {
  // The enclosing circle of a sphere's image: f R / z [px], less when partly hidden; one pixel
  // of rasterisation either way.
  const double z = camera.to_camera(point_root).z();
  const double expected_px = camera.intrinsics.fx * config_.marker_radius / z;
  return blob.circle_radius_px <= 1.3 * expected_px + 1.0 &&
         blob.circle_radius_px >= 0.3 * expected_px - 1.0;
}

Eigen::Vector3d MarkerTracker::believed_marker() const {
  return eyes_believed_.link_poses()[static_cast<std::size_t>(marker_ref_.link)] *
         marker_ref_.pose.translation();
}

bool MarkerTracker::marker_expected_in_view(const std::vector<render::Camera>& cameras) const {
  const Eigen::Vector3d p = believed_marker();
  for (const render::Camera& c : cameras) {
    const auto uv = c.project(p);
    if (!uv || uv->x() < 0 || uv->y() < 0 || uv->x() > c.intrinsics.width - 1 ||
        uv->y() > c.intrinsics.height - 1)
      return false;
  }
  return true;
}

void MarkerTracker::lose(double dt_s) {
  stimulus_->present = false;
  ++lost_;
  if (lost_ >= config_.reset_after_lost)
    kalman_.reset();
  else if (dt_s > 0)
    kalman_.predict(dt_s);
  stimulus_->position = kalman_.position();
  stimulus_->velocity = kalman_.velocity();
}

void MarkerTracker::step(NodeContext& ctx) {
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

  // The cameras where the believed head and eye kinematics put them.
  const std::vector<render::Camera> cams = eyes_believed_.pose(joints_->position);

  // Candidate blobs of each image, and the in-range pixels (to tell a wrong range).
  const auto blobs = [&](const Image& image, int& matched) {
    std::vector<vision::MarkerBlob> b =
        vision::segment_blobs(image.data, range_, config_.min_area_px, kMaxBlobs);
    matched =
        b.empty() ? vision::segment_marker(image.data, range_, 1).matched_px : b.front().matched_px;
    return b;
  };
  int matched_l = 0, matched_r = 0;
  const std::vector<vision::MarkerBlob> lb = blobs(*left_, matched_l);
  const std::vector<vision::MarkerBlob> rb = blobs(*right_, matched_r);

  const bool expected = marker_expected_in_view(cams);
  if (expected) ++expected_;
  if (expected && matched_l == 0 && matched_r == 0) {
    if (no_colour_++ == 0) no_colour_since_s_ = left_->time_s;
    if (config_.no_colour_frames_error > 0 && no_colour_ >= config_.no_colour_frames_error)
      throw RunError(fmt::format(
          "no pixel of camera '{}' or '{}' has been in the colour range {} for {} frames "
          "(since t = {:.3f} s), while the believed kinematics put the marker ('{}') in view "
          "of both: is the range the marker's colour (OpenCV HSV: H 0-179, S and V 0-255)?",
          eyes_believed_.names()[0], eyes_believed_.names()[1], range_text_, no_colour_,
          no_colour_since_s_, config_.marker_frame));
  } else {
    no_colour_ = 0;
  }

  // The pair of blobs that is the marker: rays that meet (lowest reprojection error within
  // max_reprojection_px) at a depth where a sphere of marker_radius looks as large as the blobs.
  const vision::MarkerBlob* best_l = nullptr;
  const vision::MarkerBlob* best_r = nullptr;
  vision::Triangulation best;
  const Eigen::Vector3d believed = believed_marker();
  bool rejected_far = false;
  for (const vision::MarkerBlob& l : lb)
    for (const vision::MarkerBlob& r : rb) {
      const Eigen::Vector2d ul = use_circle_ ? l.circle_centre_px : l.centroid_px;
      const Eigen::Vector2d ur = use_circle_ ? r.circle_centre_px : r.centroid_px;
      const vision::Triangulation t = vision::triangulate(cams[0], ul, cams[1], ur);
      if (!t.valid || t.reprojection_error_px > config_.max_reprojection_px) continue;
      if (best_l && t.reprojection_error_px >= best.reprojection_error_px) continue;
      if (!looks_like_marker(cams[0], l, t.point) || !looks_like_marker(cams[1], r, t.point))
        continue;
      if (config_.max_distance_from_believed > 0 &&
          (t.point - believed).norm() > config_.max_distance_from_believed) {
        rejected_far = true;
        continue;
      }
      best_l = &l, best_r = &r, best = t;
    }
  if (rejected_far && !best_l) ++far_rejections_;
  const auto eye = [](const std::vector<vision::MarkerBlob>& b, const vision::MarkerBlob* chosen) {
    const vision::MarkerBlob* shown = chosen ? chosen : (b.empty() ? nullptr : &b.front());
    if (!shown) return StereoPixels::Eye{};
    return StereoPixels::Eye{chosen != nullptr, shown->centroid_px, shown->circle_centre_px,
                             shown->area_px};
  };
  pixels_->left = eye(lb, best_l);
  pixels_->right = eye(rb, best_r);
  pixels_->frame = left_->frame;
  if (!best_l) return lose(dt);
  const vision::Triangulation& t = best;
  if (dt <= 0.0) kalman_.reset();  // the first image, or no time between images: start afresh
  kalman_.update(t.point, dt > 0.0 ? dt : ctx.period_s());
  lost_ = 0;
  ++tracked_;
  if (expected) ++expected_tracked_;
  reprojection_sum_ += t.reprojection_error_px;
  reprojection_max_ = std::max(reprojection_max_, t.reprojection_error_px);
  stimulus_->present = true;
  stimulus_->position = kalman_.position();
  stimulus_->velocity = kalman_.velocity();
  stimulus_->radius = config_.marker_radius;
  if (truth_) score_against_truth(dt);
}

void MarkerTracker::score_against_truth(double dt_s) {
  if (truth_->poses.size() != static_cast<std::size_t>(model_->num_links()))
    throw RunError(
        fmt::format("input 'true_link_poses': expected {} link poses (robot '{}'), got {}",
                    model_->num_links(), model_->name(), truth_->poses.size()));
  const Eigen::Vector3d p =
      truth_->poses[static_cast<std::size_t>(marker_ref_.link)] * marker_ref_.pose.translation();
  position_sq_sum_ += (stimulus_->position - p).squaredNorm();
  ++position_count_;
  // The true velocity: finite difference over consecutive tracked frames.
  if (has_last_truth_ && dt_s > 0.0 && last_truth_frame_ + 1 == frames_) {
    const Eigen::Vector3d true_velocity = (p - last_truth_) / dt_s;
    velocity_sq_sum_ += (stimulus_->velocity - true_velocity).squaredNorm();
    ++velocity_count_;
    lag_.add(stimulus_->position - p, true_velocity);
  }
  last_truth_ = p;
  last_truth_frame_ = frames_;
  has_last_truth_ = true;
}

void MarkerTracker::finish(NodeContext& ctx) {
  ctx.report_metric("frames", frames_);
  ctx.report_metric("frames_tracked", tracked_);
  ctx.report_metric("tracked_share",
                    frames_ ? static_cast<double>(tracked_) / static_cast<double>(frames_) : 0.0);
  ctx.report_metric("frames_in_view", expected_);
  ctx.report_metric(
      "in_view_tracked_share",
      expected_ ? static_cast<double>(expected_tracked_) / static_cast<double>(expected_) : 0.0);
  ctx.report_metric("reprojection_mean_px",
                    tracked_ ? reprojection_sum_ / static_cast<double>(tracked_) : 0.0);
  ctx.report_metric("reprojection_max_px", reprojection_max_);
  if (config_.max_distance_from_believed > 0)
    ctx.report_metric("far_from_believed_rejections", far_rejections_);
  if (truth_) {
    ctx.report_metric(
        "position_rms_m",
        position_count_ ? std::sqrt(position_sq_sum_ / static_cast<double>(position_count_)) : 0.0);
    ctx.report_metric(
        "velocity_rms_m_s",
        velocity_count_ ? std::sqrt(velocity_sq_sum_ / static_cast<double>(velocity_count_)) : 0.0);
    ctx.report_metric("latency_s", lag_.seconds());
  }
}

}  // namespace somasim::plugins
