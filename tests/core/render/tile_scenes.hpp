#pragma once
// Shared by the hypothesis-tile tests: a camera looking down the root's x axis, poses from a
// position and a rotation vector, and the message of an InputError.
#include <functional>
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
