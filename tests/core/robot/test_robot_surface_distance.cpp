// surface_distance against brute force: random poses and points around spheres, boxes and
// cylinders, compared with the distance to densely sampled surface points (outside) and an
// inside test (the sign).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "somasim/robot/surface_distance.hpp"

using somasim::ObjectShape;
using somasim::robot::ObjectGeometry;
using somasim::robot::surface_distance;

namespace {

// Points on the surface of the origin-centred shape (local frame), about `step` apart.
std::vector<Eigen::Vector3d> surface_points(const ObjectGeometry& g, double step) {
  std::vector<Eigen::Vector3d> out;
  if (g.shape == ObjectShape::kBox) {
    const Eigen::Vector3d h = g.size;
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {-1.0, 1.0}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (double a = -h[u]; a <= h[u] + 1e-12; a += step)
          for (double b = -h[v]; b <= h[v] + 1e-12; b += step) {
            Eigen::Vector3d p;
            p[axis] = side * h[axis];
            p[u] = a;
            p[v] = b;
            out.push_back(p);
          }
      }
  } else if (g.shape == ObjectShape::kCylinder) {
    const double r = g.size.x(), h = g.size.y();
    const int n = static_cast<int>(2 * M_PI * r / step) + 8;
    for (int k = 0; k < n; ++k) {
      const double a = 2 * M_PI * k / n;
      for (double z = -h; z <= h + 1e-12; z += step)
        out.emplace_back(r * std::cos(a), r * std::sin(a), z);
      for (double rr = 0; rr <= r + 1e-12; rr += step)
        for (const double z : {-h, h}) out.emplace_back(rr * std::cos(a), rr * std::sin(a), z);
    }
  }
  return out;
}

bool inside(const ObjectGeometry& g, const Eigen::Vector3d& p) {
  if (g.shape == ObjectShape::kBox) return (p.cwiseAbs() - g.size).maxCoeff() < 0;
  return std::hypot(p.x(), p.y()) < g.size.x() && std::abs(p.z()) < g.size.y();
}

}  // namespace

TEST(SurfaceDistance, BoxesAndCylindersMatchBruteForceAtRandomPosesAndPoints) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> half(0.01, 0.06), coord(-0.12, 0.12);
  const double step = 0.0005;
  for (const ObjectShape shape : {ObjectShape::kBox, ObjectShape::kCylinder}) {
    for (int trial = 0; trial < 6; ++trial) {
      ObjectGeometry g;
      g.shape = shape;
      g.size = Eigen::Vector3d(half(rng), half(rng), half(rng));
      const auto surface = surface_points(g, step);
      const Eigen::Isometry3d pose =
          Eigen::Translation3d(coord(rng), coord(rng), coord(rng)) *
          Eigen::AngleAxisd(coord(rng) * 20, Eigen::Vector3d::Random().normalized());
      for (int k = 0; k < 40; ++k) {
        const Eigen::Vector3d local(coord(rng), coord(rng), coord(rng));
        double nearest = 1e9;
        for (const auto& s : surface) nearest = std::min(nearest, (s - local).norm());
        const double expected = inside(g, local) ? -nearest : nearest;
        EXPECT_NEAR(surface_distance(g, pose, pose * local), expected, step)
            << (shape == ObjectShape::kBox ? "box" : "cylinder") << " at " << local.transpose();
      }
    }
  }
}

TEST(SurfaceDistance, SpheresAreExactAndUnknownShapesUseTheBoundingSphere) {
  ObjectGeometry ball;
  ball.shape = ObjectShape::kSphere;
  ball.size = Eigen::Vector3d(0.03, 0, 0);
  const Eigen::Isometry3d pose(Eigen::Translation3d(0.1, 0.2, 0.3));
  EXPECT_NEAR(surface_distance(ball, pose, Eigen::Vector3d(0.1, 0.2, 0.4)), 0.07, 1e-15);
  EXPECT_NEAR(surface_distance(ball, pose, Eigen::Vector3d(0.1, 0.21, 0.3)), -0.02, 1e-15);
  ObjectGeometry mesh;  // kMesh: only a bounding radius is known
  mesh.bounding_radius = 0.05;
  EXPECT_NEAR(surface_distance(mesh, pose, Eigen::Vector3d(0.1, 0.2, 0.4)), 0.05, 1e-15);
}
