#include "somasim/body_schema/pose_error.hpp"

#include <numbers>

namespace somasim::body_schema {

double orientation_error_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  // ‖logm(R)‖_F = √2 · θ for a rotation by θ about any axis.
  const Eigen::AngleAxisd relative(a.transpose() * b);
  return relative.angle() * 180.0 / std::numbers::pi;
}

double position_error_mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() * 1000.0;
}

}  // namespace somasim::body_schema
