#pragma once
// Shared by the hypothesis-tile tests: a camera looking down the root's x axis, poses from a
// position and a rotation vector, and the message of an InputError.
#include <functional>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "somasim/error.hpp"
#include "somasim/render/camera.hpp"

namespace somasim::render::testing {

/// Looks along root +x from the origin (root z up), 320 × 240, near 0.02 m, far 5 m.
inline Camera eye() {
  Camera c;
  c.name = "eye";
  c.intrinsics = {320, 240, 257.34, 257.34, 159.5, 119.5, 0.02, 5.0};
  c.pose_root.linear().col(0) = -Eigen::Vector3d::UnitY();
  c.pose_root.linear().col(1) = -Eigen::Vector3d::UnitZ();
  c.pose_root.linear().col(2) = Eigen::Vector3d::UnitX();
  return c;
}

/// root <- object: at `position` [m], turned by `rotation_vector` [rad].
inline Eigen::Isometry3d pose(const Eigen::Vector3d& position,
                              const Eigen::Vector3d& rotation_vector) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = position;
  if (rotation_vector.norm() > 0)
    p.linear() =
        Eigen::AngleAxisd(rotation_vector.norm(), rotation_vector.normalized()).toRotationMatrix();
  return p;
}

/// Two boxes' poses (root <- box): the big one 0.25-0.4 m ahead of eye(), turned up to ~25°;
/// the small one's centre up to ±lateral_y, ±lateral_z [m] from the big one's along the big
/// box's y and z axes, moved `depth_shift` [m] along the line of sight (negative: nearer the
/// camera), turned up to ~35°.
struct TwoBoxes {
  Eigen::Isometry3d big, small;
};
inline TwoBoxes two_boxes(std::mt19937& rng, double depth_shift, double lateral_y,
                          double lateral_z) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d centre(0.32 + 0.07 * u(rng), 0.05 * u(rng), 0.04 * u(rng));
  TwoBoxes s;
  s.big = pose(centre, Eigen::Vector3d(0.4 * u(rng), 0.4 * u(rng), 0.4 * u(rng)));
  const Eigen::Vector3d lateral =
      s.big.linear() * Eigen::Vector3d(0.0, lateral_y * u(rng), lateral_z * u(rng));
  const Eigen::Vector3d at = centre + lateral;
  s.small = pose(at + depth_shift * at.normalized(),
                 Eigen::Vector3d(0.6 * u(rng), 0.6 * u(rng), 0.6 * u(rng)));
  return s;
}

/// The message of the InputError `f` throws; "no error" when it throws none.
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace somasim::render::testing
