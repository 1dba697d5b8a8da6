#pragma once
/// @file
/// Stimulus coordinates in a taxel frame: distance D [m] and time to contact TTC [s].
///
/// Frames: the root frame is the robot's root (world-fixed during a contact event); a taxel
/// frame has its origin at the taxel centre and its z axis along the outward skin normal. The
/// rotation about the normal does not affect D or TTC; it is fixed deterministically by
/// taxel_rotation().
#include <Eigen/Core>

namespace somasim::pps {

/// A taxel: centre [m] and outward unit normal, both expressed in one frame (root or link).
struct TaxelPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// A stimulus (an approaching object or a fingertip) at one instant, in the root frame. The
/// same type travels on `stimulus` ports (pps/ports.hpp), where `present` says whether anything
/// is perceived now; the geometry below ignores `present`.
struct Stimulus {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< centre [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< [m/s]
  double radius = 0.0;                                 ///< [m]
  bool present = false;                                ///< false: nothing perceived now
};

/// How TTC is computed from p (position) and v (velocity) in the taxel frame.
enum class TtcDefinition {
  /// TTC = -|p|^2 / (p.v): distance over closing speed. Receding (p.v >= 0) => invalid.
  kSigned,
  /// TTC = |p| / |v|: distance over speed; always >= 0, kept also behind the skin plane.
  /// Invalid only when |v| = 0.
  kUnsigned,
};

/// Rotation R (root <- taxel) whose third column is the normalised `normal`. The x axis is the
/// root axis least aligned with the normal (X, then Y, then Z on ties), made orthogonal to it.
Eigen::Matrix3d taxel_rotation(const Eigen::Vector3d& normal);

/// Stimulus in a taxel frame: p = R^T (centre - taxel position) - radius * z; v = R^T velocity.
struct TaxelFrameStimulus {
  Eigen::Vector3d p;  ///< [m]
  Eigen::Vector3d v;  ///< [m/s]
};

/// Expresses `s` in the frame of `taxel` (both in the same frame, normally root).
TaxelFrameStimulus to_taxel_frame(const TaxelPose& taxel, const Stimulus& s);

/// D [m] and TTC [s]; `valid` is false when TTC is undefined for the chosen definition.
struct DTtc {
  double d = 0.0;
  double ttc = 0.0;
  bool valid = false;
};

/// D = sign(p_z) |p| (p_z = 0 counts as +), TTC per `def`.
DTtc compute_d_ttc(const Eigen::Vector3d& p, const Eigen::Vector3d& v, TtcDefinition def);

}  // namespace somasim::pps
