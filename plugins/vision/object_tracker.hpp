#pragma once
// object_tracker: the generic object tracker of the PPS study (Roncone et al. 2016, Fig 13)
// seen by both eyes: motion detection by optical flow acquires an object, a CamShift tracker of
// its hue-saturation distribution follows it in each image, the two centres are triangulated
// through the believed head/eye kinematics, and a Kalman filter (constant acceleration by
// default) gives position and velocity; a pps::Stimulus in the root frame. The head may move
// (gaze_controller): the cameras are posed at the images' render time, the previous image and
// search windows follow the camera's own rotation, and the robot's own colours, fixes beyond
// max_distance_m, fixes beyond max_jump_m of the filter's prediction (the trackers slid onto
// clutter when the object went) and two eyes on unlike colours are refused; an eye's track that
// gives no stereo fix for unfixed_frames_lost frames is dropped, and of two tracks of unlike
// areas the smaller one at once.
#include <array>
#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "believed_eyes.hpp"
#include "lag_estimate.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/render/camera.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"
#include "somasim/vision/colour_tracker.hpp"
#include "somasim/vision/kalman_tracker.hpp"
#include "somasim/vision/motion_detection.hpp"
#include "somasim/vision/ports.hpp"

namespace somasim::plugins {

class ObjectTracker : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    BelievedEyes::Config eyes;
    double min_flow_px = 0.5;  // [px]
    int min_motion_px = 20;
    double max_motion_fraction = 0.3;
    int still_frames_lost = 20;
    double still_px = 1.5;  // [px]
    double max_background_ratio = 1.0;
    bool refuse_own_colours = true;
    bool compensate_ego_motion = true;
    int min_saturation = 60;
    int min_value = 30;
    int min_object_px = 12;
    double lost_fraction = 0.3;
    double max_reprojection_px = 4.0;  // [px]
    double max_jump_m = 0.08;          // [m]
    double max_distance_m = 0.8;       // [m]
    double max_colour_distance = 0.6;
    int inconsistent_frames_lost = 2;
    int unfixed_frames_lost = 10;
    int reset_after_lost = 3;
    double radius_min = 0.005;  // [m]
    double radius_max = 0.2;    // [m]
    bool predict_windows = false;
    // the Kalman filter (motion_model, process_noise, measurement_sigma), with this
    // tracker's defaults
    vision::KalmanOptions kalman{.model = vision::MotionModel::kConstantAcceleration,
                                 .measurement_sigma_m = 0.005};
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    BelievedEyes::Inputs eyes;  // left_eye_rgb, right_eye_rgb, joint_state
    OptionalIn<pps::Stimulus> truth;
    Out<pps::Stimulus> stimulus;
    Out<StereoPixels> object_pixels;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  struct Eye {
    vision::ColourTracker tracker;
    cv::Mat previous;                   // the last image (for the flow)
    Eigen::Matrix3d previous_rotation;  // its believed camera rotation (root <- camera)
    vision::ColourTrack track;
    // Motion consistency: where the track was when it last moved (carried along by the
    // camera's own rotation), its radius then, and the frames since.
    Eigen::Vector2d anchor_px = Eigen::Vector2d::Zero();
    double anchor_radius_px = 0.0;
    int still_frames = 0;
    int unfixed_frames = 0;  // consecutive frames tracked without a stereo fix
  };
  /// One eye's CamShift step (or acquisition by motion); `dt_s` [s] since the previous image.
  void track_eye(Eye& eye, const Image& image, const render::Camera& camera, double dt_s);
  /// Drops each eye's track that gave no stereo fix for unfixed_frames_lost_ frames; `fixed`:
  /// this frame made one.
  void drop_unfixed(bool fixed);
  void lose(double dt_s);
  void score_against_truth(const std::vector<render::Camera>& cameras);
  /// The encoder values at the sim time closest to `time_s` among the recent steps [rad, m].
  const Eigen::VectorXd& joints_at(double time_s);

  std::shared_ptr<const robot::RobotModel> model_;
  BelievedEyes eyes_believed_;  // cameras and the believed head/eye kinematics
  vision::MotionOptions motion_;
  bool compensate_ego_motion_ = true;
  double max_motion_fraction_ = 0.0;
  int still_frames_lost_ = 0;
  double still_px_ = 0.0;
  double max_reprojection_px_ = 0.0;
  int inconsistent_frames_lost_ = 0;
  int unfixed_frames_lost_ = 0;
  double max_distance_ = 0.0;  // [m] from the middle of the eyes
  double max_jump_ = 0.0;      // [m] from the filter's prediction
  double max_colour_distance_ = 0.0;
  int reset_after_lost_ = 0;
  double radius_min_ = 0.0, radius_max_ = 0.0;
  bool predict_windows_ = false;
  vision::KalmanTracker kalman_;
  std::array<Eye, 2> eyes_;

  const Image* left_ = nullptr;
  const Image* right_ = nullptr;
  const JointState* joints_ = nullptr;
  const pps::Stimulus* truth_ = nullptr;  // optional
  pps::Stimulus* stimulus_ = nullptr;
  StereoPixels* pixels_ = nullptr;

  std::uint64_t last_frame_ = 0;
  double last_time_s_ = 0.0;
  int lost_ = 0;          // consecutive frames without a fix
  int inconsistent_ = 0;  // consecutive frames both eyes tracked but the rays did not meet
  std::int64_t frames_ = 0, tracked_ = 0, acquisitions_ = 0, losses_ = 0, inconsistent_drops_ = 0;
  std::int64_t still_drops_ = 0, refused_ = 0;  // static tracks dropped, acquisitions refused
  std::int64_t own_colour_refused_ = 0;         // of those: the robot's own colours
  std::int64_t far_drops_ = 0;                  // fixes beyond max_distance_m
  std::int64_t jump_drops_ = 0;                 // fixes beyond max_jump_m of the prediction
  std::int64_t colour_mismatches_ = 0;          // both eyes tracked things of unlike colours
  std::int64_t unfixed_drops_ = 0;              // tracks dropped after unfixed_frames_lost
  std::int64_t area_drops_ = 0;                 // smaller tracks dropped for unlike areas
  // Recent (sim time [s], encoder values): the head's pose when an image was rendered.
  std::deque<std::pair<double, Eigen::VectorXd>> joint_history_;
  double pose_time_offset_max_s_ = 0.0;  // largest |image time - pose time| used [s]
  std::int64_t partial_ = 0;             // both tracked, but cut by the border or of unlike areas
  std::int64_t partial_border_ = 0;      // of those: cut by the border
  double reprojection_sum_ = 0.0;
  // Against the truth: frames it is present / in view of both eyes (believed cameras) and
  // tracked among them; errors over tracked frames with the truth present.
  std::int64_t truth_frames_ = 0, truth_tracked_ = 0, in_view_ = 0, in_view_tracked_ = 0;
  std::int64_t false_fixes_ = 0, error_count_ = 0;
  double position_sq_sum_ = 0.0, velocity_sq_sum_ = 0.0;
  LagEstimate lag_{0.01};  // latency; truth slower than 1 cm/s left out
};

}  // namespace somasim::plugins
