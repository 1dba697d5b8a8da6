// The paper's orientation error equals ‖logm(R_Aᵀ R_B)‖_F / √2; positions in millimetres.
#include <gtest/gtest.h>

#include <numbers>

#include "somasim/body_schema/pose_error.hpp"

namespace somasim::body_schema {
namespace {

// ‖logm(R)‖_F / √2 computed from the skew matrix of the axis-angle vector.
double frobenius_of_log(const Eigen::Matrix3d& r) {
  const Eigen::AngleAxisd aa(r);
  const Eigen::Vector3d w = aa.axis() * aa.angle();
  Eigen::Matrix3d skew;
  skew << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return skew.norm() / std::sqrt(2.0) * 180.0 / std::numbers::pi;
}

TEST(PoseError, OrientationIsTheRelativeAngleInDegrees) {
  const Eigen::Matrix3d a =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (double deg : {0.5, 7.0, 45.0, 170.0}) {
    const Eigen::Matrix3d b = a * Eigen::AngleAxisd(deg * std::numbers::pi / 180.0,
                                                    Eigen::Vector3d(0, 1, -1).normalized())
                                      .toRotationMatrix();
    EXPECT_NEAR(orientation_error_deg(a, b), deg, 1e-9);
    EXPECT_NEAR(orientation_error_deg(b, a), deg, 1e-9);
    EXPECT_NEAR(orientation_error_deg(a, b), frobenius_of_log(a.transpose() * b), 1e-9);
  }
  EXPECT_NEAR(orientation_error_deg(a, a), 0.0, 1e-9);
}

TEST(PoseError, PositionInMillimetres) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = Eigen::Isometry3d::Identity();
  a.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
  b.translation() = Eigen::Vector3d(0.103, 0.196, 0.3);
  EXPECT_NEAR(position_error_mm(a, b), 5.0, 1e-9);
}

}  // namespace
}  // namespace somasim::body_schema
