#include "somasim/vision/stereo_object_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "somasim/vision/stereo_object.hpp"

namespace somasim::vision {
namespace {

constexpr int kMaxAreaRatio = 3;  // of the two eyes' object areas for one object

// A track cut by the image border has an unknown centre.
bool at_border(const ColourTrack& t, const cv::Mat& image) {
  const Eigen::Vector2d& c = t.centre_px;
  return c.x() - t.radius_px < 1 || c.y() - t.radius_px < 1 ||
         c.x() + t.radius_px > image.cols - 2 || c.y() + t.radius_px > image.rows - 2;
}

}  // namespace

StereoObjectTracker::StereoObjectTracker(const StereoTrackerOptions& options)
    : options_(options), kalman_(options.kalman), window_(options.velocity_window_fixes) {
  for (Eye& eye : eyes_) eye.tracker = ColourTracker(options_.colour);
}

void StereoObjectTracker::track_eye(Eye& eye, const cv::Mat& image, const render::Camera& camera,
                                    double dt_s) {
  const auto& k = camera.intrinsics;
  const cv::Matx33d ego =
      options_.compensate_ego_motion && !eye.previous.empty()
          ? rotation_homography(eye.previous_rotation, camera.pose_root.linear(), k.fx, k.fy, k.cx,
                                k.cy)
          : cv::Matx33d::eye();
  if (eye.tracker.tracking()) {
    cv::Matx33d shift = ego;  // the head's own turn
    if (options_.predict_windows && kalman_.initialised() && lost_ < options_.reset_after_lost &&
        dt_s > 0)
      shift = predicted_image_shift(camera, kalman_.position(), kalman_.velocity(), dt_s) *
              ego;  // and the object's own motion
    eye.tracker.shift_window(shift);
  }
  eye.track = eye.tracker.tracking() ? eye.tracker.track(image) : ColourTrack{};
  if (!eye.track.tracked && !eye.tracker.tracking() && eye.track.window.area() > 0)
    ++counts_.losses;
  if (eye.track.tracked) {
    // Motion consistency: a static thing of the object's colour is not the object.
    const cv::Vec3d a = ego * cv::Vec3d(eye.anchor_px.x(), eye.anchor_px.y(), 1.0);
    const Eigen::Vector2d anchor(a[0] / a[2], a[1] / a[2]);
    if ((eye.track.centre_px - anchor).norm() > options_.still_px ||
        std::abs(eye.track.radius_px - eye.anchor_radius_px) > options_.still_px) {
      eye.anchor_px = eye.track.centre_px;
      eye.anchor_radius_px = eye.track.radius_px;
      eye.still_frames = 0;
    } else if (++eye.still_frames >= options_.still_frames_lost) {
      eye.tracker.lose();
      eye.track.tracked = false;
      ++counts_.still_drops;
    } else {
      eye.anchor_px = anchor;
    }
  }
  if (!eye.track.tracked && !eye.previous.empty()) {
    const MotionBlob m = detect_motion(eye.previous, image, options_.motion, ego);
    const double image_px = static_cast<double>(image.total());
    if (m.found && m.area_px <= options_.max_motion_fraction * image_px) {
      if (eye.tracker.acquire(image, m.mask)) {
        ++counts_.acquisitions;
        eye.track = eye.tracker.track(image);
        eye.anchor_px = eye.track.centre_px;
        eye.anchor_radius_px = eye.track.radius_px;
        eye.still_frames = 0;
      } else {
        ++counts_.refused;
        if (eye.tracker.last_refusal() == Refusal::kOwnColour) ++counts_.own_colour_refused;
      }
    } else if (m.found) {
      ++counts_.refused;
    }
  }
  image.copyTo(eye.previous);
  eye.previous_rotation = camera.pose_root.linear();
}

void StereoObjectTracker::drop_unfixed(bool fixed) {
  for (Eye& eye : eyes_) {
    eye.unfixed_frames = fixed || !eye.tracker.tracking() ? 0 : eye.unfixed_frames + 1;
    if (eye.unfixed_frames >= options_.unfixed_frames_lost) {
      eye.tracker.lose();
      eye.unfixed_frames = 0;
      ++counts_.unfixed_drops;
    }
  }
}

void StereoObjectTracker::drop_both() {
  for (Eye& eye : eyes_) eye.tracker.lose();
}

StereoFix StereoObjectTracker::update(const cv::Mat& left, const cv::Mat& right,
                                      const std::array<render::Camera, 2>& cameras, double dt_s,
                                      double first_dt_s) {
  ++counts_.frames;
  clock_s_ += std::max(dt_s, 0.0);
  track_eye(eyes_[0], left, cameras[0], dt_s);
  track_eye(eyes_[1], right, cameras[1], dt_s);
  StereoFix out;
  out.tracks = {eyes_[0].track, eyes_[1].track};

  const ColourTrack& l = eyes_[0].track;
  const ColourTrack& r = eyes_[1].track;
  StereoObject object;
  out.outcome = l.tracked ? (r.tracked ? FixOutcome::kFixed : FixOutcome::kLeftOnly)
                          : (r.tracked ? FixOutcome::kRightOnly : FixOutcome::kNoTrack);
  const bool comparable =
      l.tracked && r.tracked &&
      std::max(l.object_px, r.object_px) <= kMaxAreaRatio * std::min(l.object_px, r.object_px);
  const bool border = l.tracked && r.tracked && (at_border(l, left) || at_border(r, right));
  if (l.tracked && r.tracked && (border || !comparable)) {
    ++counts_.partial;
    counts_.partial_border += border ? 1 : 0;
    out.outcome = border ? FixOutcome::kBorder : FixOutcome::kUnlikeAreas;
    // Unlike areas, neither cut by the border: one eye holds something else (e.g. clutter its
    // tracker slid onto when the last object went). The smaller track is dropped and its eye
    // re-acquires by motion; the object, if that was it, is moving and is found again.
    if (!border) {
      eyes_[l.object_px < r.object_px ? 0 : 1].tracker.lose();
      ++counts_.area_drops;
    }
  } else if (l.tracked && r.tracked) {
    object = triangulate_object(cameras[0], l.centre_px, l.radius_px, cameras[1], r.centre_px,
                                r.radius_px);
    const bool same_colours =
        colour_distance(eyes_[0].tracker, eyes_[1].tracker) <= options_.max_colour_distance;
    if (!same_colours) ++counts_.colour_mismatches;
    out.size_ratio = object.size_ratio;
    const bool triangulated =
        object.centre.valid && object.centre.reprojection_error_px <= options_.max_reprojection_px;
    const bool like_sizes =
        options_.max_size_ratio <= 0.0 || object.size_ratio <= options_.max_size_ratio;
    if (triangulated && same_colours && !like_sizes) ++counts_.size_mismatches;
    const Eigen::Vector3d middle =
        0.5 * (cameras[0].pose_root.translation() + cameras[1].pose_root.translation());
    if (!triangulated || !same_colours || !like_sizes) {
      out.outcome = !triangulated   ? FixOutcome::kNotTriangulated
                    : !same_colours ? FixOutcome::kColourMismatch
                                    : FixOutcome::kUnlikeSizes;
      object.centre.valid = false;
      if (++inconsistent_ >= options_.inconsistent_frames_lost) {  // re-acquire both by motion
        drop_both();
        ++counts_.inconsistent_drops;
        inconsistent_ = 0;
      }
    } else if ((object.centre.point - middle).norm() > options_.max_distance_m) {
      object.centre.valid = false;  // the backdrop, not an object near the body
      out.outcome = FixOutcome::kTooFar;
      drop_both();
      ++counts_.far_drops;
      inconsistent_ = 0;
    } else if ((lost_ == 0 || options_.jump_check_after_missed) &&
               lost_ < options_.reset_after_lost && kalman_.initialised() && dt_s > 0.0 &&
               (object.centre.point - (kalman_.position() + dt_s * kalman_.velocity())).norm() >
                   options_.max_jump_m) {
      object.centre.valid = false;  // not the object of the previous frame
      out.outcome = FixOutcome::kJump;
      drop_both();
      ++counts_.jump_drops;
      inconsistent_ = 0;
    } else {
      inconsistent_ = 0;
    }
  }
  drop_unfixed(object.centre.valid);
  if (!object.centre.valid) {
    ++lost_;
    if (lost_ >= options_.reset_after_lost) {
      kalman_.reset();
      window_.clear();
    } else if (dt_s > 0)
      kalman_.predict(dt_s);
  } else {
    if (dt_s <= 0.0 || lost_ >= options_.reset_after_lost) {
      kalman_.reset();
      window_.clear();
    }
    kalman_.update(object.centre.point, dt_s > 0.0 ? dt_s : first_dt_s);
    window_.add(clock_s_, object.centre.point, object.radius_m);
    lost_ = 0;
    ++counts_.fixes;
    counts_.reprojection_sum_px += object.centre.reprojection_error_px;
    out.fixed = true;
    out.radius_m = object.radius_m;
    out.reprojection_px = object.centre.reprojection_error_px;
  }
  out.position = kalman_.position();
  out.velocity = kalman_.velocity();
  out.velocity_sigma = kalman_.velocity_sigma().maxCoeff();
  out.window_velocity = window_.velocity();
  out.window_fixes = window_.size();
  out.window_radius_rate = window_.radius_rate();
  return out;
}

}  // namespace somasim::vision
