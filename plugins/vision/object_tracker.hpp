#pragma once
// object_tracker: the generic object tracker of the PPS study (Roncone et al. 2016, Fig 13)
// seen by both eyes: vision::StereoObjectTracker (motion acquisition, CamShift per eye,
// triangulation, Kalman filter and the checks that refuse what is not the object) fed with the
// cameras where the believed head/eye kinematics put them when the images were rendered (the
// head may move, gaze_controller); a pps::Stimulus in the root frame, and with a wired truth
// the tracking errors, latency and shares of frames tracked.
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
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
#include "somasim/vision/kalman_tracker.hpp"
#include "somasim/vision/ports.hpp"
#include "somasim/vision/settling_gate.hpp"
#include "somasim/vision/stereo_object_tracker.hpp"
#include "tracker_trace.hpp"

namespace somasim::plugins {

class ObjectTracker : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    BelievedEyes::Config eyes;
    // Defaults: vision::StereoTrackerOptions{} and its motion and colour options.
    double min_flow_px = defaults().motion.min_flow_px;  // [px]
    int min_motion_px = defaults().motion.min_area_px;
    double max_motion_fraction = defaults().max_motion_fraction;
    int still_frames_lost = defaults().still_frames_lost;
    double still_px = defaults().still_px;  // [px]
    double max_background_ratio = defaults().colour.max_background_ratio;
    bool refuse_own_colours = true;
    bool compensate_ego_motion = defaults().compensate_ego_motion;
    int min_saturation = defaults().colour.min_saturation;
    int min_value = defaults().colour.min_value;
    int min_object_px = defaults().colour.min_object_px;
    double lost_fraction = defaults().colour.lost_fraction;
    double max_reprojection_px = defaults().max_reprojection_px;  // [px]
    double max_jump_m = defaults().max_jump_m;                    // [m]
    bool jump_check_after_missed = defaults().jump_check_after_missed;
    double max_distance_m = defaults().max_distance_m;  // [m]
    double max_colour_distance = defaults().max_colour_distance;
    double max_size_ratio = defaults().max_size_ratio;
    int inconsistent_frames_lost = defaults().inconsistent_frames_lost;
    int unfixed_frames_lost = defaults().unfixed_frames_lost;
    int reset_after_lost = defaults().reset_after_lost;
    double radius_min = 0.005;  // [m]
    double radius_max = 0.2;    // [m]
    bool predict_windows = defaults().predict_windows;
    double max_velocity_sigma = 0.0;  // [m/s]; 0: the velocity is always reported
    int velocity_window_fixes = defaults().velocity_window_fixes;
    double max_velocity_disagreement = 0.0;  // [m/s]; 0: no check against the track's fixes
    double max_radius_rate = 0.0;            // [1/s]; 0: no check of the track's radius
    double velocity_over_settling = 0.0;     // 0: no check of the speed against the radius'
    // the Kalman filter (motion_model, process_noise, measurement_sigma)
    vision::KalmanOptions kalman = defaults().kalman;
    OutputFile trace{"", {}};  // per-frame CSV in the run folder; "" = none
    static const vision::StereoTrackerOptions& defaults();
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
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
  void score_against_truth(const std::array<render::Camera, 2>& cameras);
  /// Whether `fix`'s velocity is known well enough to report (max_velocity_sigma,
  /// max_radius_rate, velocity_over_settling, max_velocity_disagreement); counts the unsettled,
  /// settling-explained and disputed ones. Called on every fix.
  bool velocity_is_known(const vision::StereoFix& fix);
  /// The encoder values at the sim time closest to `time_s` among the recent steps [rad, m].
  const Eigen::VectorXd& joints_at(double time_s);

  std::shared_ptr<const robot::RobotModel> model_;
  BelievedEyes eyes_believed_;  // cameras and the believed head/eye kinematics
  vision::StereoObjectTracker tracker_;
  std::optional<vision::SettlingGate> settling_;  // with max_radius_rate
  std::optional<TrackerTrace> trace_;             // with a trace file named

  const Image* left_ = nullptr;
  const Image* right_ = nullptr;
  const JointState* joints_ = nullptr;
  const pps::Stimulus* truth_ = nullptr;  // optional
  pps::Stimulus* stimulus_ = nullptr;
  StereoPixels* pixels_ = nullptr;

  std::uint64_t last_frame_ = 0;
  double last_time_s_ = 0.0;
  // Recent (sim time [s], encoder values): the head's pose when an image was rendered.
  std::deque<std::pair<double, Eigen::VectorXd>> joint_history_;
  double pose_time_offset_max_s_ = 0.0;  // largest |image time - pose time| used [s]
  // Against the truth: frames it is present / in view of both eyes (believed cameras) and
  // tracked among them; errors over tracked frames with the truth present.
  std::int64_t truth_frames_ = 0, truth_tracked_ = 0, in_view_ = 0, in_view_tracked_ = 0;
  std::int64_t false_fixes_ = 0, error_count_ = 0;
  std::int64_t velocity_withheld_frames_ = 0;  // fixes reported without their velocity
  std::int64_t velocity_disputed_frames_ = 0;  // of those: the track's fixes disagreed
  std::int64_t radius_unsettled_frames_ = 0;   // of those: the track's radius was changing
  std::int64_t velocity_settling_frames_ = 0;  // of those: slower than the radius' change explains
  double position_sq_sum_ = 0.0, velocity_sq_sum_ = 0.0;
  LagEstimate lag_{0.01};  // latency; truth slower than 1 cm/s left out
};

}  // namespace somasim::plugins
