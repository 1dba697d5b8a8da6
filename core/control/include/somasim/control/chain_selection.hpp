#pragma once
/// @file
/// Which dofs and links of a RobotModel a controller may use: a serial chain given by name
/// (a chain of the description, e.g. "right_arm") or by its base link and tip frame/link.
#include <string>
#include <vector>

#include "somasim/robot/robot_model.hpp"

namespace somasim::control {

struct ChainSelection {
  std::string name;        ///< the chain's name, or "base->tip"
  std::vector<int> dofs;   ///< model dof indices of the chain joints, base → tip
  std::vector<int> links;  ///< model links moved by the chain dofs only: the links from the
                           ///< base (excluded) to the tip link, plus links fixed to them
  std::vector<std::string> link_names;
  int tip_link = -1;  ///< the link of the tip frame (the default controlled link)

  bool contains_link(int link) const;
  /// Index of `link_name` if it is in the chain; InputError otherwise:
  /// "robot 'r': unknown link 'x' (did you mean 'y'?)" or
  /// "link 'x' is not in chain 'right_arm' (links: a, b, c)".
  int require_link(const robot::RobotModel& model, const std::string& link_name) const;
};

/// A named chain of the description; InputError "robot 'r': unknown chain 'x' (did you mean..)".
ChainSelection select_chain(const robot::RobotModel& model, const std::string& chain_name);
/// The chain from `base` (a link; "" = the root) to `tip` (a frame or link); InputError when a
/// name is unknown or the tip does not descend from the base.
ChainSelection select_chain(const robot::RobotModel& model, const std::string& tip,
                            const std::string& base);

}  // namespace somasim::control
