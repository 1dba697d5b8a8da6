#pragma once
/// @file
/// Receptive field (RF) of a taxel, in the taxel frame (z = outward normal) [m].
#include <span>

#include <Eigen/Core>

#include "somasim/name_table.hpp"

namespace somasim::pps {

enum class RfShape {
  /// Cone above the skin: 0 <= z <= range_m and radial distance <= z tan(half_angle).
  kCone,
  /// Released code: the cone, its mirror image below the skin (-range_m <= z < 0), and a
  /// cylinder |z| <= cylinder_half_height_m, radial distance <= cylinder_radius_m.
  kConeMirroredCylinder,
};
inline constexpr NamedValue<RfShape> kRfShapeNames[] = {
    {RfShape::kCone, "cone"}, {RfShape::kConeMirroredCylinder, "cone_mirrored_cylinder"}};
/// "cone", "cone_mirrored_cylinder".
constexpr std::span<const NamedValue<RfShape>> name_table(RfShape) {
  return kRfShapeNames;
}

struct ReceptiveField {
  RfShape shape = RfShape::kCone;
  double half_angle_rad = 50.0 * 3.14159265358979323846 / 180.0;  ///< from the normal
  double range_m = 0.20;                  ///< cone height along the normal [m]
  double cylinder_half_height_m = 0.075;  ///< [m] (kConeMirroredCylinder only)
  double cylinder_radius_m = 0.0894;      ///< [m] (kConeMirroredCylinder only)

  static ReceptiveField paper() { return ReceptiveField{}; }
  static ReceptiveField code() {
    ReceptiveField rf;
    rf.shape = RfShape::kConeMirroredCylinder;
    return rf;
  }
};

/// True when `p_taxel_frame` [m] lies inside `rf` (boundaries included).
bool in_receptive_field(const Eigen::Vector3d& p_taxel_frame, const ReceptiveField& rf);

}  // namespace somasim::pps

namespace somasim::pps {

/// `ReceptiveField` with its trigonometry precomputed, for tight loops.
class PreparedRf {
 public:
  explicit PreparedRf(const ReceptiveField& rf);
  /// Same result as in_receptive_field(p, rf).
  bool contains(const Eigen::Vector3d& p) const {
    const double z = p.z();
    const double rho2 = p.x() * p.x() + p.y() * p.y();
    if (mirrored_) {
      if (z <= cyl_h_ && z >= -cyl_h_ && rho2 <= cyl_r2_) return true;
      const double az = z < 0.0 ? -z : z;
      return az <= range_ && rho2 <= tan2_ * az * az;
    }
    return z >= 0.0 && z <= range_ && rho2 <= tan2_ * z * z;
  }

 private:
  bool mirrored_;
  double range_, tan2_, cyl_h_, cyl_r2_;
};

}  // namespace somasim::pps
