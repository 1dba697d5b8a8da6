#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "somasim/pps/stimulus.hpp"

using namespace somasim::pps;

TEST(PpsStimulus, RotationIsOrthonormalWithZAlongNormal) {
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0),
                                   Eigen::Vector3d(0.3, -0.4, 2.0), Eigen::Vector3d(0, -1, 0)}) {
    const Eigen::Matrix3d r = taxel_rotation(n);
    EXPECT_TRUE((r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    EXPECT_TRUE(r.col(2).isApprox(n.normalized(), 1e-12));
    EXPECT_TRUE(taxel_rotation(n).isApprox(r));  // deterministic
  }
}

TEST(PpsStimulus, PositionMinusRadiusAlongNormal) {
  TaxelPose t{Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 2)};
  Stimulus s{Eigen::Vector3d(1, 2, 3.10), Eigen::Vector3d(0, 0, -0.1), 0.02};
  const auto ts = to_taxel_frame(t, s);
  EXPECT_NEAR(ts.p.z(), 0.08, 1e-12);
  EXPECT_NEAR(ts.p.head<2>().norm(), 0.0, 1e-12);
  EXPECT_NEAR(ts.v.z(), -0.1, 1e-12);
}

TEST(PpsStimulus, VelocityTransformedAsDirectionNotPoint) {
  // Taxel far from the origin, normal along +x: a velocity along -x is a pure approach in the
  // taxel frame regardless of the taxel's position.
  TaxelPose t{Eigen::Vector3d(5, -3, 7), Eigen::Vector3d(1, 0, 0)};
  Stimulus s{Eigen::Vector3d(5.1, -3, 7), Eigen::Vector3d(-0.2, 0, 0), 0.0};
  const auto ts = to_taxel_frame(t, s);
  EXPECT_TRUE(ts.v.isApprox(Eigen::Vector3d(0, 0, -0.2), 1e-12));
  const DTtc dt = compute_d_ttc(ts.p, ts.v, TtcDefinition::kSigned);
  ASSERT_TRUE(dt.valid);
  EXPECT_NEAR(dt.d, 0.1, 1e-12);
  EXPECT_NEAR(dt.ttc, 0.5, 1e-12);
}

TEST(PpsStimulus, SignedTtc) {
  const Eigen::Vector3d p(0.03, 0.0, 0.04);  // |p| = 0.05
  const DTtc a = compute_d_ttc(p, Eigen::Vector3d(0, 0, -0.1), TtcDefinition::kSigned);
  ASSERT_TRUE(a.valid);
  EXPECT_NEAR(a.d, 0.05, 1e-12);
  EXPECT_NEAR(a.ttc, 0.0025 / 0.004, 1e-12);  // -|p|^2 / (p.v)
  // Receding and tangential motions are dropped.
  EXPECT_FALSE(compute_d_ttc(p, Eigen::Vector3d(0, 0, 0.1), TtcDefinition::kSigned).valid);
  EXPECT_FALSE(compute_d_ttc(p, Eigen::Vector3d(0, 0.1, 0), TtcDefinition::kSigned).valid);
  EXPECT_FALSE(compute_d_ttc(p, Eigen::Vector3d::Zero(), TtcDefinition::kSigned).valid);
}

TEST(PpsStimulus, NegativeDBehindSkin) {
  const Eigen::Vector3d p(0.0, 0.0, -0.02);
  const DTtc s = compute_d_ttc(p, Eigen::Vector3d(0, 0, 0.1), TtcDefinition::kSigned);
  ASSERT_TRUE(s.valid);  // approaching the taxel from behind
  EXPECT_NEAR(s.d, -0.02, 1e-12);
  EXPECT_NEAR(s.ttc, 0.2, 1e-12);
}

TEST(PpsStimulus, UnsignedTtcKeepsRecedingAndBehind) {
  const Eigen::Vector3d p(0.0, 0.0, -0.03);
  const DTtc u = compute_d_ttc(p, Eigen::Vector3d(0, 0, -0.1), TtcDefinition::kUnsigned);
  ASSERT_TRUE(u.valid);  // receding behind the skin plane: kept
  EXPECT_NEAR(u.d, -0.03, 1e-12);
  EXPECT_NEAR(u.ttc, 0.3, 1e-12);
  EXPECT_FALSE(compute_d_ttc(p, Eigen::Vector3d::Zero(), TtcDefinition::kUnsigned).valid);
}
