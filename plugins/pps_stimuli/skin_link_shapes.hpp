#pragma once
/// @file
/// Which collision shapes of a skin part's own link an object aimed at the part could meet
/// before its skin: the link's shapes but the one the taxels lie on (e.g. a hand's thumb and
/// fingers beside the palm's skin).
#include <vector>

#include <Eigen/Geometry>

#include "somasim/robot/geometry.hpp"

namespace somasim::plugins {

/// The shapes of `link_shapes` (collision primitives of the link that carries a skin part, in
/// its frame) other than the one the taxels lie on: the primitive nearest to the taxels
/// (`taxel_positions_link` [m, link frame]; least mean |surface distance|). Meshes count as
/// beside the skin (their distance is unknown) but are never the skin's own. Empty when the
/// link has one shape or no taxel is given.
std::vector<robot::Geometry> shapes_beside_skin(
    const std::vector<robot::Geometry>& link_shapes,
    const std::vector<Eigen::Vector3d>& taxel_positions_link);

}  // namespace somasim::plugins
