#include "somasim/robot/surface_distance.hpp"

#include <algorithm>
#include <cmath>

namespace somasim::robot {

namespace {

// Signed distance from the origin-centred box of half extents `half` to `p` (local frame).
double box_distance(const Eigen::Vector3d& half, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// Same for the origin-centred cylinder of radius r and half height h along z.
double cylinder_distance(double r, double h, const Eigen::Vector3d& p) {
  const Eigen::Vector2d q(std::hypot(p.x(), p.y()) - r, std::abs(p.z()) - h);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

}  // namespace

double surface_distance(const ObjectGeometry& g, const Eigen::Isometry3d& pose,
                        const Eigen::Vector3d& point) {
  switch (g.shape) {
    case ObjectShape::kSphere:
      return (point - pose.translation()).norm() - g.size.x();
    case ObjectShape::kBox:
      return box_distance(g.size, pose.inverse() * point);
    case ObjectShape::kCylinder:
      return cylinder_distance(g.size.x(), g.size.y(), pose.inverse() * point);
    case ObjectShape::kMesh:
      break;
  }
  return (point - pose.translation()).norm() - g.bounding_radius;
}

}  // namespace somasim::robot
