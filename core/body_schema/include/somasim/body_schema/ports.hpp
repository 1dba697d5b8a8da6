#pragma once
/// @file
/// Port value types of the body-schema study: the phase of a reaching movement (from the
/// reach_controller, so that the filter restarts with every movement) and the filter's estimate.
/// Frames: the left-eye frame is the robot model's `left_eye` camera frame (x right, y down,
/// z along the optical axis); units [m], [rad] unless a name says otherwise.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "somasim/port_type.hpp"

namespace somasim {

/// Where a reaching movement stands.
enum class ReachStage : std::uint8_t {
  kIdle = 0,        ///< no movement yet, or all done
  kToStart = 1,     ///< moving to the movement's start posture (not observed by the filter)
  kOpenLoop = 2,    ///< linear joint trajectory to the nominal IK solution
  kClosedLoop = 3,  ///< visual servoing with the adapted model
};

struct ReachPhase {
  int movement = -1;  ///< 0, 1, ... ; -1 before the first
  ReachStage stage = ReachStage::kIdle;
  int frame = 0;  ///< frames since the start of the open loop (1 = first observed frame)
  Eigen::Isometry3d target_eye = Eigen::Isometry3d::Identity();  ///< desired palm, left eye
};

/// The body-schema filter's estimate after its last frame.
struct BodySchemaEstimate {
  std::uint64_t frame = 0;  ///< filter frames so far; 0 = no estimate yet
  int movement = -1;        ///< the movement it belongs to (ReachPhase::movement)
  Eigen::VectorXd offsets;  ///< β̂ [rad] per model dof (0 for joints not estimated)
  /// K(θ + β̂): estimated palm pose in the left-eye frame [m].
  Eigen::Isometry3d palm_eye = Eigen::Isometry3d::Identity();
  double sigma_deg = 0.0;  ///< σ_s of the frame's prediction [deg]
  double best_likelihood = 0.0;
  double mean_likelihood = 0.0;
  double effective_sample_size = 0.0;
};

template <>
struct PortTraits<ReachPhase> {
  static constexpr const char* name = "reach_phase";
  static constexpr const char* header = "somasim/body_schema/ports.hpp";
  static std::vector<std::string> csv_columns(const ReachPhase&) {
    return {"movement", "stage (0 idle, 1 to start, 2 open loop, 3 closed loop)", "frame"};
  }
  static void csv_write(const ReachPhase& p, std::string& row) {
    csv_append(row, static_cast<double>(p.movement));
    csv_append(row, static_cast<double>(p.stage));
    csv_append(row, static_cast<double>(p.frame));
  }
};

template <>
struct PortTraits<BodySchemaEstimate> {
  static constexpr const char* name = "body_schema_estimate";
  static constexpr const char* header = "somasim/body_schema/ports.hpp";
};

}  // namespace somasim
