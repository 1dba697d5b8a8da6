#pragma once
// marker_tracker: a coloured marker (the iCub's green right index fingertip) seen by both eyes:
// HSV segmentation in each image, stereo triangulation through the believed head/eye
// kinematics, a Kalman filter for position and velocity; a pps::Stimulus in the root frame.
#include <memory>
#include <span>
#include <string>
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
#include "somasim/vision/marker_segmentation.hpp"
#include "somasim/vision/ports.hpp"

namespace somasim::plugins {

/// Where in its blob the marker is measured.
enum class BlobCentre : std::uint8_t { kCircle, kCentroid };
/// "circle", "centroid".
inline constexpr NamedValue<BlobCentre> kBlobCentreNames[] = {{BlobCentre::kCircle, "circle"},
                                                              {BlobCentre::kCentroid, "centroid"}};
constexpr std::span<const NamedValue<BlobCentre>> name_table(BlobCentre) {
  return kBlobCentreNames;
}

class MarkerTracker : public Plugin {
 public:
  struct Config {
    robot::RobotParam robot;
    BelievedEyes::Config eyes;
    std::vector<double> hsv_low{45, 80, 40};
    std::vector<double> hsv_high{75, 255, 255};
    int min_area_px = 6;
    double marker_radius = 0.007;  // [m]
    std::string marker_frame = "r_index_tip";
    double max_distance_from_believed = 0.06;  // [m]
    BlobCentre blob_centre = BlobCentre::kCircle;
    double max_reprojection_px = 3.0;  // [px]
    int no_colour_frames_error = 10;
    int reset_after_lost = 5;
    // the Kalman filter (motion_model, process_noise, measurement_sigma), with this
    // tracker's defaults
    vision::KalmanOptions kalman{.model = vision::MotionModel::kConstantVelocity,
                                 .measurement_sigma_m = 0.003};
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    BelievedEyes::Inputs eyes;  // left_eye_rgb, right_eye_rgb, joint_state
    OptionalIn<LinkPoses> true_link_poses;
    Out<pps::Stimulus> stimulus;
    Out<StereoPixels> marker_pixels;
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
  bool looks_like_marker(const render::Camera& camera, const vision::MarkerBlob& blob,
                         const Eigen::Vector3d& point_root) const;
  /// Where the believed kinematics (encoders + joint_offsets_deg) put marker_frame [m, root].
  Eigen::Vector3d believed_marker() const;
  bool marker_expected_in_view(const std::vector<render::Camera>& cameras) const;
  void lose(double dt_s);
  void score_against_truth(
      double dt_s);  // a tracked frame against true_link_poses  // a frame without a fix

  static constexpr std::size_t kMaxBlobs = 8;  // candidate blobs per image, largest first

  std::shared_ptr<const robot::RobotModel> model_;
  BelievedEyes eyes_believed_;  // cameras and the believed head/eye kinematics
  vision::HsvRange range_;
  std::string range_text_;
  bool use_circle_ = true;      // blob_centre: circle
  robot::FrameRef marker_ref_;  // where the marker is (marker_frame)
  vision::KalmanTracker kalman_;

  const Image* left_ = nullptr;
  const Image* right_ = nullptr;
  const JointState* joints_ = nullptr;
  const LinkPoses* truth_ = nullptr;  // optional
  pps::Stimulus* stimulus_ = nullptr;
  StereoPixels* pixels_ = nullptr;

  std::uint64_t last_frame_ = 0;
  double last_time_s_ = 0.0;
  int lost_ = 0;       // consecutive frames without a fix
  int no_colour_ = 0;  // consecutive frames without any pixel in range while expected in view
  double no_colour_since_s_ = 0.0;
  std::int64_t frames_ = 0, tracked_ = 0, expected_ = 0, expected_tracked_ = 0;
  std::int64_t far_rejections_ = 0;  // frames whose only marker-like pairs were far from belief
  double reprojection_sum_ = 0.0, reprojection_max_ = 0.0;
  // Against the truth (true_link_poses), over tracked frames.
  double position_sq_sum_ = 0.0, velocity_sq_sum_ = 0.0;
  std::int64_t position_count_ = 0, velocity_count_ = 0, last_truth_frame_ = 0;
  Eigen::Vector3d last_truth_ = Eigen::Vector3d::Zero();
  bool has_last_truth_ = false;
  LagEstimate lag_{0.01};  // latency; truth slower than 1 cm/s left out
};

}  // namespace somasim::plugins
