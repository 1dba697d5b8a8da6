#include "somasim/pps/receptive_field.hpp"

#include <cmath>

namespace somasim::pps {

PreparedRf::PreparedRf(const ReceptiveField& rf)
    : mirrored_(rf.shape == RfShape::kConeMirroredCylinder),
      range_(rf.range_m),
      tan2_(std::tan(rf.half_angle_rad) * std::tan(rf.half_angle_rad)),
      cyl_h_(rf.cylinder_half_height_m),
      cyl_r2_(rf.cylinder_radius_m * rf.cylinder_radius_m) {}

bool in_receptive_field(const Eigen::Vector3d& p_taxel_frame, const ReceptiveField& rf) {
  return PreparedRf(rf).contains(p_taxel_frame);
}

}  // namespace somasim::pps
