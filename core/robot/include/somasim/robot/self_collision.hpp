#pragma once
/// @file
/// Which pairs of robot links are never tested against each other for collision (the rule every
/// physics back end and exporter shares).
///
/// Links joined by fixed joints, or by joints locked at their initial value, form one rigid group:
/// its links never collide with each other. A group is also exempt against its nearest ancestor
/// group that has collision geometry: joints through geometry-less frame links (the DH chains'
/// intermediate links) do not separate them. So the forearm and the upper arm touching at the
/// elbow are exempt, while the two arms, or a hand and the chest, collide.
#include <vector>

#include "somasim/robot/robot_model.hpp"

namespace somasim::robot {

/// exempt[a][b] (link indices, symmetric) is true when links a and b are never tested against
/// each other. `locked`: per dof, joints locked at their initial value (empty: none).
std::vector<std::vector<bool>> collision_exempt_links(const RobotModel& model,
                                                      const std::vector<bool>& locked = {});

}  // namespace somasim::robot
