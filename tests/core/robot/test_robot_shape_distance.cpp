// robot::shape_distance on generated pairs of primitives against distances known in closed form
// (spheres, a sphere and a box, cylinder or capsule) or by a fine search (two capsules).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "somasim/robot/clearance.hpp"
#include "somasim/robot/shape_distance.hpp"

using somasim::robot::distance_to_shape;
using somasim::robot::Geometry;
using somasim::robot::GeometryType;
using somasim::robot::shape_distance;

namespace {

Eigen::Isometry3d random_pose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized())
                      .toRotationMatrix();
  pose.translation() = spread * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return pose;
}

Geometry random_shape(GeometryType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> size(0.005, 0.04);
  Geometry g;
  g.type = type;
  g.radius = size(rng);
  g.length = 2.0 * size(rng);
  g.size = Eigen::Vector3d(2.0 * size(rng), 2.0 * size(rng), 2.0 * size(rng));
  g.origin = random_pose(rng, 0.01);
  return g;
}

// The ends of a capsule's axis in the root frame.
std::pair<Eigen::Vector3d, Eigen::Vector3d> axis_of(const Geometry& g,
                                                    const Eigen::Isometry3d& link) {
  const Eigen::Isometry3d pose = link * g.origin;
  return {pose * Eigen::Vector3d(0, 0, -0.5 * g.length),
          pose * Eigen::Vector3d(0, 0, 0.5 * g.length)};
}

// Distance between two segments by a grid over both parameters, refined around the best cell
// until the cells are below 1e-9 of the segments' parameter.
double segment_distance(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& s,
                        const std::pair<Eigen::Vector3d, Eigen::Vector3d>& t) {
  double s0 = 0.0, s1 = 1.0, t0 = 0.0, t1 = 1.0, best = std::numeric_limits<double>::infinity();
  for (int level = 0; level < 12; ++level) {
    double bs = 0.0, bt = 0.0;
    constexpr int kCells = 40;
    for (int i = 0; i <= kCells; ++i)
      for (int j = 0; j <= kCells; ++j) {
        const double a = s0 + (s1 - s0) * i / kCells, b = t0 + (t1 - t0) * j / kCells;
        const double d =
            ((s.first + a * (s.second - s.first)) - (t.first + b * (t.second - t.first))).norm();
        if (d < best) best = d, bs = a, bt = b;
      }
    const double ws = 2.0 * (s1 - s0) / kCells, wt = 2.0 * (t1 - t0) / kCells;
    s0 = std::max(0.0, bs - ws), s1 = std::min(1.0, bs + ws);
    t0 = std::max(0.0, bt - wt), t1 = std::min(1.0, bt + wt);
  }
  return best;
}

}  // namespace

TEST(ShapeDistance, ASphereAgainstEveryPrimitiveIsItsCentresDistanceLessItsRadius) {
  std::mt19937 rng(11);
  int apart = 0;
  for (const GeometryType type :
       {GeometryType::Sphere, GeometryType::Box, GeometryType::Cylinder, GeometryType::Capsule})
    for (int k = 0; k < 100; ++k) {
      const Geometry sphere = random_shape(GeometryType::Sphere, rng);
      const Geometry other = random_shape(type, rng);
      const Eigen::Isometry3d a_link = random_pose(rng, 0.08), b_link = random_pose(rng, 0.08);
      const Eigen::Vector3d centre = a_link * sphere.origin.translation();
      const double expected =
          std::max(0.0, distance_to_shape(other, b_link.inverse() * centre) - sphere.radius);
      // Both orders: the sphere projected first, and the other shape first.
      EXPECT_NEAR(shape_distance(sphere, a_link, other, b_link), expected, 1e-7)
          << "type " << static_cast<int>(type) << ", pair " << k;
      EXPECT_NEAR(shape_distance(other, b_link, sphere, a_link), expected, 1e-7)
          << "type " << static_cast<int>(type) << ", pair " << k;
      apart += expected > 0.0 ? 1 : 0;
    }
  EXPECT_GT(apart, 200);  // most pairs apart, some overlapping
}

TEST(ShapeDistance, TwoCapsulesAreTheirAxesDistanceLessTheirRadii) {
  std::mt19937 rng(12);
  int apart = 0;
  for (int k = 0; k < 200; ++k) {
    const Geometry a = random_shape(GeometryType::Capsule, rng);
    const Geometry b = random_shape(GeometryType::Capsule, rng);
    const Eigen::Isometry3d a_link = random_pose(rng, 0.08), b_link = random_pose(rng, 0.08);
    const double expected = std::max(
        0.0, segment_distance(axis_of(a, a_link), axis_of(b, b_link)) - a.radius - b.radius);
    EXPECT_NEAR(shape_distance(a, a_link, b, b_link), expected, 1e-6) << "pair " << k;
    apart += expected > 0.0 ? 1 : 0;
  }
  EXPECT_GT(apart, 100);
}

TEST(ShapeDistance, TwoFlatEndedCylindersFaceToFace) {
  // Coaxial, end faces 3 mm apart; then tilted so that only the rims come close.
  Geometry finger;
  finger.type = GeometryType::Cylinder;
  finger.radius = 0.0065;
  finger.length = 0.08;
  Eigen::Isometry3d b_link = Eigen::Isometry3d::Identity();
  b_link.translation() = Eigen::Vector3d(0, 0, 0.083);
  EXPECT_NEAR(shape_distance(finger, Eigen::Isometry3d::Identity(), finger, b_link), 0.003, 1e-9);
  b_link.translation() = Eigen::Vector3d(0, 0.02, 0.079);  // side by side, overlapping in z
  EXPECT_NEAR(shape_distance(finger, Eigen::Isometry3d::Identity(), finger, b_link), 0.007, 1e-9);
  b_link.translation() = Eigen::Vector3d(0, 0.005, 0.079);  // the ends overlap
  EXPECT_EQ(shape_distance(finger, Eigen::Isometry3d::Identity(), finger, b_link), 0.0);
  Geometry mesh;
  mesh.type = GeometryType::Mesh;
  EXPECT_TRUE(std::isinf(shape_distance(finger, b_link, mesh, b_link)));
}
