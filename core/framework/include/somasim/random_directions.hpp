#pragma once
/// @file
/// Random directions for stimulus sources (thrown balls, approaching objects).
#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

namespace somasim {

/// A unit direction drawn uniformly over the spherical cap of half-angle `half_angle_rad`
/// [rad] around the unit vector `axis` (any frame; the result is in the same frame). Draws two
/// uniform numbers from `rng`, in a fixed order, so streams stay reproducible.
template <class Rng>
Eigen::Vector3d sample_direction_in_cone(const Eigen::Vector3d& axis, double half_angle_rad,
                                         Rng& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double cos_t = 1.0 - unit(rng) * (1.0 - std::cos(half_angle_rad));
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  const double phi = 2.0 * M_PI * unit(rng);
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  return cos_t * axis + sin_t * (std::cos(phi) * u + std::sin(phi) * v);
}

}  // namespace somasim
