#pragma once
/// @file
/// Angle units. somasim's rule: internally every angle is in radians; every angle a user
/// writes (a plugin parameter, a robot or scene file key) is in degrees and its name ends in
/// `_deg` (parameters also declare the unit "deg"). Convert at the boundary with these helpers.
#include <cmath>

namespace somasim {

/// Radians per degree, for code that scales many values by one factor.
inline constexpr double kRadPerDeg = M_PI / 180.0;

/// `deg` [deg] in radians; computed as deg·π/180 (multiplication first).
constexpr double deg_to_rad(double deg) {
  return deg * M_PI / 180.0;
}

/// `rad` [rad] in degrees; computed as rad·180/π (multiplication first).
constexpr double rad_to_deg(double rad) {
  return rad * 180.0 / M_PI;
}

}  // namespace somasim
