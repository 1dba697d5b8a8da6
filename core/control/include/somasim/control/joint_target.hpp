#pragma once
/// @file
/// A joint-space goal for a trajectory generator (joint_trajectory's optional `target` input):
/// reach `position` on the active dofs in `duration_s`. Producers bump `id` for each new goal;
/// consumers start a new trajectory when they see an id they have not seen.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "somasim/port_type.hpp"

namespace somasim {

struct JointTarget {
  std::uint64_t id = 0;      ///< 0: no target yet; strictly increasing per producer
  std::vector<bool> active;  ///< per dof (model dof order): whether this target sets the dof
  Eigen::VectorXd position;  ///< [rad] ([m] prismatic) per dof; read where active
  double duration_s = 1.0;   ///< time to reach the target from the current reference [s], > 0
};

template <>
struct PortTraits<JointTarget> {
  static constexpr const char* name = "joint_target";
};

}  // namespace somasim
