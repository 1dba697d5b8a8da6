#include "somasim/robot/shape_distance.hpp"

#include <cmath>
#include <limits>

#include "somasim/robot/clearance.hpp"

namespace somasim::robot {
namespace {

// The point of the solid `shape` (posed by `link`: root <- link) closest to `p` [m, root frame]:
// p itself inside, else p moved along the distance's gradient by the (exact) distance.
Eigen::Vector3d project(const Geometry& shape, const Eigen::Isometry3d& link,
                        const Eigen::Isometry3d& link_from_root, const Eigen::Vector3d& p) {
  const Eigen::Vector3d local = link_from_root * p;
  const double d = distance_to_shape(shape, local);
  if (d <= 0.0) return p;
  constexpr double kStep = 1e-7;  // [m], central differences
  Eigen::Vector3d gradient;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[k] = kStep;
    gradient[k] = distance_to_shape(shape, local + e) - distance_to_shape(shape, local - e);
  }
  if (gradient.norm() == 0.0) return p;
  return link * (local - d * gradient.normalized());
}

}  // namespace

double shape_distance(const Geometry& a, const Eigen::Isometry3d& a_link, const Geometry& b,
                      const Eigen::Isometry3d& b_link) {
  if (a.type == GeometryType::Mesh || b.type == GeometryType::Mesh)
    return std::numeric_limits<double>::infinity();
  constexpr double kTouching = 1e-9;  // [m]
  const Eigen::Isometry3d a_from_root = a_link.inverse(Eigen::Isometry);
  const Eigen::Isometry3d b_from_root = b_link.inverse(Eigen::Isometry);
  Eigen::Vector3d on_a = a_link * a.origin.translation();
  Eigen::Vector3d on_b = project(b, b_link, b_from_root, on_a);
  for (int round = 0; round < 1000; ++round) {
    if ((on_b - on_a).norm() <= kTouching) return 0.0;  // a point of a lies in b
    const Eigen::Vector3d next_a = project(a, a_link, a_from_root, on_b);
    if ((next_a - on_b).norm() <= kTouching) return 0.0;  // a point of b lies in a
    const Eigen::Vector3d next_b = project(b, b_link, b_from_root, next_a);
    const double moved = (next_a - on_a).norm() + (next_b - on_b).norm();
    on_a = next_a;
    on_b = next_b;
    if (moved < 1e-12) break;
  }
  return (on_b - on_a).norm();
}

}  // namespace somasim::robot
