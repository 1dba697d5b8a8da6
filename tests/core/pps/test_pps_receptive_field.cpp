#include <cmath>

#include <gtest/gtest.h>

#include "somasim/pps/receptive_field.hpp"

using namespace somasim::pps;
using V = Eigen::Vector3d;

TEST(PpsReceptiveField, Cone) {
  const ReceptiveField rf = ReceptiveField::paper();
  EXPECT_TRUE(in_receptive_field(V(0, 0, 0.1), rf));
  EXPECT_TRUE(in_receptive_field(V(0, 0, 0.2), rf));
  EXPECT_FALSE(in_receptive_field(V(0, 0, 0.2001), rf));
  const double t50 = std::tan(50.0 * M_PI / 180.0);
  EXPECT_TRUE(in_receptive_field(V(0.1 * t50 * 0.999, 0, 0.1), rf));
  EXPECT_FALSE(in_receptive_field(V(0.1 * t50 * 1.001, 0, 0.1), rf));
  EXPECT_FALSE(in_receptive_field(V(0, 0, -0.01), rf));
  EXPECT_FALSE(in_receptive_field(V(0.01, 0, 0.0), rf));
}

TEST(PpsReceptiveField, HalfAngleParameter) {
  ReceptiveField rf;
  rf.half_angle_rad = 10.0 * M_PI / 180.0;
  EXPECT_FALSE(in_receptive_field(V(0.05, 0, 0.1), rf));
  rf.half_angle_rad = 30.0 * M_PI / 180.0;
  EXPECT_TRUE(in_receptive_field(V(0.05, 0, 0.1), rf));
}

TEST(PpsReceptiveField, ConeMirroredCylinder) {
  const ReceptiveField rf = ReceptiveField::code();
  EXPECT_TRUE(in_receptive_field(V(0, 0, -0.15), rf));  // mirrored cone
  EXPECT_FALSE(in_receptive_field(V(0, 0, -0.21), rf));
  EXPECT_TRUE(in_receptive_field(V(0.08, 0, 0.01), rf));  // cylinder near the skin
  EXPECT_TRUE(in_receptive_field(V(0.0, 0.08, -0.07), rf));
  EXPECT_FALSE(in_receptive_field(V(0.09, 0, 0.01), rf));  // radius 0.0894
  EXPECT_FALSE(in_receptive_field(V(0.08, 0, 0.0), ReceptiveField::paper()));
}
