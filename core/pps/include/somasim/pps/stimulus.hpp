#pragma once
/// @file
/// Stimulus coordinates in a taxel frame: distance D [m] and time to contact TTC [s].
///
/// Frames: the root frame is the robot's root (world-fixed during a contact event); a taxel
/// frame has its origin at the taxel centre and its z axis along the outward skin normal. The
/// rotation about the normal does not affect D or TTC; it is fixed deterministically by
/// taxel_rotation().
#include <span>

#include <Eigen/Core>

#include "somasim/name_table.hpp"

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
inline constexpr NamedValue<TtcDefinition> kTtcDefinitionNames[] = {
    {TtcDefinition::kSigned, "signed"}, {TtcDefinition::kUnsigned, "unsigned"}};
/// "signed", "unsigned".
constexpr std::span<const NamedValue<TtcDefinition>> name_table(TtcDefinition) {
  return kTtcDefinitionNames;
}

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

/// Where a taxel's perceived offset is measured (true_offsets.hpp, the `contact` estimator):
/// perceived D − true D when the object was this far [m] outside the touched taxel's skin
/// plane on its way in. At the contact itself D = sign(p_z)|p| jumps by 2|p| for a taxel whose
/// error is sideways (p_z ≈ 0 beside it), so there the offset has no defined sign; 5 cm out,
/// normal errors up to 5 cm keep their sign and a sideways error counts as the change of
/// distance it makes.
inline constexpr double kOffsetClearance = 0.05;
/// Longest back-off [s] along the path to reach kOffsetClearance (objects approach at >= 2 cm/s).
inline constexpr double kOffsetMaxBackoff = 2.5;

/// How long [s] before now the stimulus `s` (moving at constant velocity) was last at least
/// `clearance` [m] outside (p_z >= clearance) the skin plane of every taxel of `taxels` that it
/// moves toward: 0 when it already is, at most `max_s`. Taxels and stimulus in one frame. Used
/// to take "the moment the object reached the skin" when a skin reports a touch only once the
/// object already presses into it.
double time_since_outside(std::span<const TaxelPose> taxels, const Stimulus& s,
                          double clearance = 1e-4, double max_s = 0.1);

/// Index of the point of `points` nearest `target` (the first on ties); -1 when empty. The
/// `contact` offset estimator and its truth credit a touch to the touched taxel nearest the
/// centre of pressure: beside a contact, a touched taxel sees the stimulus sideways with
/// p_z ≈ 0, where D = sign(p_z)|p| is discontinuous and tells nothing about an offset.
int nearest_point(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& target);

/// D = sign(p_z) |p| (p_z = 0 counts as +), TTC per `def`.
DTtc compute_d_ttc(const Eigen::Vector3d& p, const Eigen::Vector3d& v, TtcDefinition def);

}  // namespace somasim::pps
