#pragma once
/// @file
/// Conversions between Eigen and Bullet (double-precision build: btScalar is double).
#include <LinearMath/btTransform.h>

#include <Eigen/Geometry>

namespace somasim::bullet_world {

static_assert(sizeof(btScalar) == sizeof(double), "bullet_world needs double-precision Bullet");

inline btVector3 to_bt(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}
inline Eigen::Vector3d to_eigen(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

inline btMatrix3x3 to_bt(const Eigen::Matrix3d& m) {
  return {m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)};
}
inline Eigen::Matrix3d to_eigen(const btMatrix3x3& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}

inline btQuaternion to_bt_quat(const Eigen::Matrix3d& m) {
  const Eigen::Quaterniond q(m);
  return {q.x(), q.y(), q.z(), q.w()};
}

inline btTransform to_bt(const Eigen::Isometry3d& t) {
  return btTransform(to_bt(Eigen::Matrix3d(t.linear())), to_bt(Eigen::Vector3d(t.translation())));
}
inline Eigen::Isometry3d to_eigen(const btTransform& t) {
  Eigen::Isometry3d r = Eigen::Isometry3d::Identity();
  r.linear() = to_eigen(t.getBasis());
  r.translation() = to_eigen(t.getOrigin());
  return r;
}

}  // namespace somasim::bullet_world
