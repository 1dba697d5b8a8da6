#pragma once
/// @file
/// The generic object tracker's state machine (the PPS study's Fig 13 pipeline) for one pair of
/// eyes: in each image a moving blob (dense optical flow) acquires an object, a CamShift colour
/// tracker follows it, the two centres are triangulated through the posed cameras, and a Kalman
/// filter gives position and velocity.
///
/// What it refuses, frame by frame:
/// - an acquisition by a blob larger than max_motion_fraction of the image (the whole scene
///   jumped) or of colours that are not distinctive or are the robot's own (ColourTracker);
/// - a track that stood still (centre and radius within still_px, beyond the camera's own
///   rotation) for still_frames_lost frames: static clutter of the object's colour;
/// - two tracks of unlike areas (more than 3 ×): the smaller one is dropped; a track cut by
///   the image border gives no fix but is kept;
/// - two tracks whose rays do not meet (reprojection error), whose colour models differ, or
///   (with max_size_ratio) whose sizes at the triangulated depth differ: after
///   inconsistent_frames_lost such frames both are dropped;
/// - a fix beyond max_distance_m of the middle of the eyes (the backdrop) or beyond max_jump_m
///   of the filter's prediction (the trackers slid onto something else): both dropped; with
///   jump_check_after_missed also the first fix after frames without one, against the prediction
///   carried through them (else the filter would join fixes of two objects into one track);
/// - an eye's track that gave no fix for unfixed_frames_lost frames.
/// A dropped track is re-acquired by motion. Without a fix the filter predicts; after
/// reset_after_lost frames without one it starts afresh.
///
/// Images are rgb8 (CV_8UC3, R G B), pixels and cameras as in somasim/render/camera.hpp; points
/// in the root frame [m], velocities [m/s], times [s].
#include <array>
#include <cstdint>
#include <span>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "somasim/name_table.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/vision/colour_tracker.hpp"
#include "somasim/vision/fix_window.hpp"
#include "somasim/vision/kalman_tracker.hpp"
#include "somasim/vision/motion_detection.hpp"

namespace somasim::vision {

struct StereoTrackerOptions {
  MotionOptions motion;         ///< acquisition by optical flow
  ColourTrackerOptions colour;  ///< each eye's CamShift tracker
  /// A moving blob larger than this fraction of the image acquires nothing.
  double max_motion_fraction = 0.3;
  /// Warp the previous image by the camera's own rotation before the flow, and carry the
  /// search windows along with it.
  bool compensate_ego_motion = true;
  int still_frames_lost = 20;        ///< frames a track may stand still before it is dropped
  double still_px = 1.5;             ///< how far a track must move to count as moving [px]
  double max_reprojection_px = 4.0;  ///< RMS reprojection error above which no fix [px]
  double max_jump_m = 0.08;          ///< from the filter's prediction [m]
  /// Check max_jump_m also on the first fix after frames without one (while the filter still
  /// predicts the track, fewer than reset_after_lost frames), not only on consecutive fixes.
  bool jump_check_after_missed = false;
  double max_distance_m = 0.8;       ///< from the middle of the two eyes [m]
  double max_colour_distance = 0.6;  ///< Bhattacharyya distance of the eyes' colour models
  /// The most the two eyes' object radii may differ once scaled to the triangulated depth
  /// (StereoObject::size_ratio, larger over smaller): two tracks whose rays meet but whose sizes
  /// there disagree hold two different things (e.g. one eye a patch of backdrop of the object's
  /// colour). 0 = no check.
  double max_size_ratio = 0.0;
  int inconsistent_frames_lost = 2;  ///< frames of two tracks that do not triangulate
  int unfixed_frames_lost = 10;      ///< frames an eye's track may give no fix
  int reset_after_lost = 3;          ///< frames without a fix before the filter starts afresh
  /// Move each search window by the image motion the filter predicts before CamShift.
  bool predict_windows = false;
  /// The fixes a straight line is fitted to (StereoFix::window_velocity), at least 2.
  int velocity_window_fixes = 5;
  KalmanOptions kalman{.model = MotionModel::kConstantAcceleration, .measurement_sigma_m = 0.005};
};

/// What happened so far (counts of frames and events).
struct StereoTrackerCounts {
  std::int64_t frames = 0;              ///< stereo frames given to update()
  std::int64_t fixes = 0;               ///< of those: frames with a fix
  std::int64_t acquisitions = 0;        ///< eye tracks started by motion
  std::int64_t losses = 0;              ///< eye tracks whose colour collapsed
  std::int64_t refused = 0;             ///< acquisitions refused (blob too large or colours)
  std::int64_t own_colour_refused = 0;  ///< of those: the robot's own colours
  std::int64_t still_drops = 0;         ///< eye tracks dropped for standing still
  std::int64_t inconsistent_drops = 0;  ///< both dropped after inconsistent frames
  std::int64_t far_drops = 0;           ///< both dropped for a fix beyond max_distance_m
  std::int64_t jump_drops = 0;          ///< both dropped for a fix beyond max_jump_m
  std::int64_t colour_mismatches = 0;   ///< frames whose two colour models differed
  std::int64_t size_mismatches = 0;     ///< frames refused for sizes beyond max_size_ratio
  std::int64_t unfixed_drops = 0;       ///< eye tracks dropped after unfixed_frames_lost
  std::int64_t area_drops = 0;          ///< smaller tracks dropped for unlike areas
  std::int64_t partial = 0;             ///< both tracked, but cut by the border or unlike areas
  std::int64_t partial_border = 0;      ///< of those: cut by the border
  double reprojection_sum_px = 0.0;     ///< over the fixes [px]
};

/// Whether a stereo frame gave a fix, and which check refused it when it did not (the first
/// that applies, in this order).
enum class FixOutcome : std::uint8_t {
  kFixed,            ///< a triangulated fix passed every check
  kNoTrack,          ///< neither eye tracks anything
  kLeftOnly,         ///< only the left eye tracks something
  kRightOnly,        ///< only the right eye tracks something
  kBorder,           ///< a track is cut by its image's border (its centre is unknown)
  kUnlikeAreas,      ///< the eyes' areas differ more than 3:1 (one holds something else)
  kNotTriangulated,  ///< the rays do not meet within max_reprojection_px
  kColourMismatch,   ///< the eyes' colour models differ more than max_colour_distance
  kUnlikeSizes,      ///< the eyes' sizes at the fix's depth differ more than max_size_ratio
  kTooFar,           ///< beyond max_distance_m (the backdrop)
  kJump,             ///< farther than max_jump_m from the track's prediction
};
/// "fixed", "no_track", "left_only", "right_only", "border", "unlike_areas",
/// "not_triangulated", "colour_mismatch", "unlike_sizes", "too_far", "jump" (enum_name()).
inline constexpr NamedValue<FixOutcome> kFixOutcomeNames[] = {
    {FixOutcome::kFixed, "fixed"},
    {FixOutcome::kNoTrack, "no_track"},
    {FixOutcome::kLeftOnly, "left_only"},
    {FixOutcome::kRightOnly, "right_only"},
    {FixOutcome::kBorder, "border"},
    {FixOutcome::kUnlikeAreas, "unlike_areas"},
    {FixOutcome::kNotTriangulated, "not_triangulated"},
    {FixOutcome::kColourMismatch, "colour_mismatch"},
    {FixOutcome::kUnlikeSizes, "unlike_sizes"},
    {FixOutcome::kTooFar, "too_far"},
    {FixOutcome::kJump, "jump"}};
constexpr std::span<const NamedValue<FixOutcome>> name_table(FixOutcome) {
  return kFixOutcomeNames;
}

/// One stereo frame's outcome.
struct StereoFix {
  bool fixed = false;                         ///< a triangulated fix passed every check
  FixOutcome outcome = FixOutcome::kNoTrack;  ///< kFixed, or the check that refused the frame
  /// The filter's state after the frame (updated by the fix, else predicted, or zero after a
  /// reset) [m], [m/s].
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  /// The filter's σ of the velocity, largest over the axes [m/s] (0 after a reset).
  double velocity_sigma = 0.0;
  /// The slope of the least-squares line through the last fixes of this track (since the
  /// filter's last reset, at most velocity_window_fixes) [m/s], and how many it went through.
  Eigen::Vector3d window_velocity = Eigen::Vector3d::Zero();
  int window_fixes = 0;
  /// How fast the radius of those fixes changes, over its mean [1/s] (FixWindow::radius_rate): a
  /// rigid object's is 0; a track still settling onto its object grows or shrinks.
  double window_radius_rate = 0.0;
  double radius_m = 0.0;  ///< from the tracked areas and the depth; 0 unfixed
  /// StereoObject::size_ratio of the two tracks (whether or not the frame was fixed); 0 when
  /// they did not triangulate.
  double size_ratio = 0.0;
  double reprojection_px = 0.0;       ///< RMS reprojection error of the fix [px]
  std::array<ColourTrack, 2> tracks;  ///< each eye's track this frame (left, right)
};

class StereoObjectTracker {
 public:
  /// Throws somasim::InputError for options the colour tracker refuses.
  explicit StereoObjectTracker(const StereoTrackerOptions& options = {});

  /// One stereo frame: `left` and `right` (rgb8 images of the cameras' sizes) seen by `cameras`
  /// (posed where they were when the images were taken); `dt_s` [s] since the previous frame,
  /// 0 for the first; `first_dt_s` [s] is the filter's step for a fix without a previous frame.
  StereoFix update(const cv::Mat& left, const cv::Mat& right,
                   const std::array<render::Camera, 2>& cameras, double dt_s, double first_dt_s);

  const StereoTrackerCounts& counts() const { return counts_; }
  const StereoTrackerOptions& options() const { return options_; }

 private:
  struct Eye {
    ColourTracker tracker;
    cv::Mat previous;                                                 // the last image
    Eigen::Matrix3d previous_rotation = Eigen::Matrix3d::Identity();  // root <- camera
    ColourTrack track;
    // Where the track was when it last moved (carried along by the camera's own rotation),
    // its radius then, and the frames since.
    Eigen::Vector2d anchor_px = Eigen::Vector2d::Zero();
    double anchor_radius_px = 0.0;
    int still_frames = 0;
    int unfixed_frames = 0;  // consecutive frames tracked without a fix
  };
  void track_eye(Eye& eye, const cv::Mat& image, const render::Camera& camera, double dt_s);
  void drop_unfixed(bool fixed);
  void drop_both();

  StereoTrackerOptions options_;
  KalmanTracker kalman_;
  FixWindow window_;      // this track's last fixes
  double clock_s_ = 0.0;  // the sum of the frames' dt_s [s]
  std::array<Eye, 2> eyes_;
  int lost_ = 0;          // consecutive frames without a fix
  int inconsistent_ = 0;  // consecutive frames of two tracks that did not triangulate
  StereoTrackerCounts counts_;
};

}  // namespace somasim::vision
