#pragma once
/// @file
/// Which robot links the presented objects touched, from the world's contacts: every link
/// counts, with skin or without (the head, the upper arm, a hand's back), so that an object that
/// meets the robot where no taxel can feel it is reported, not silently pressed on.
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "somasim/plugin.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

class RobotContactLog {
 public:
  /// Links that carry a skin patch of `model` count as skinned.
  explicit RobotContactLog(const robot::RobotModel& model);

  /// Logs the contacts of `contacts.recent` newer than the last call between the object named
  /// `object` (looked up in `objects`) and robot links, for presentation `presentation`.
  /// Returns the sim-time [s] of the presentation's first robot contact when this call found it.
  std::optional<double> add(const Contacts& contacts, const ObjectStates& objects,
                            const std::string& object, std::uint64_t presentation);

  /// Links the last add() found touched for the first time in its presentation, in order.
  const std::vector<int>& newly_touched() const { return newly_touched_; }

  int presentations_touching() const { return touching_; }
  int presentations_touching_unskinned() const { return touching_unskinned_; }
  /// Per link without skin: presentations that touched it.
  const std::map<std::string, int>& unskinned_links() const { return unskinned_links_; }

  /// Metrics robot_contact_presentations, robot_contact_unskinned_presentations and
  /// robot_contact_unskinned_links ({link: presentations}).
  void report(NodeContext& ctx) const;

 private:
  const robot::RobotModel& model_;
  std::vector<bool> skinned_;  // per link
  double last_time_s_ = -1.0;  // contacts up to this time are logged
  std::uint64_t presentation_ = 0;
  std::set<int> links_;  // links the current presentation touched
  std::vector<int> newly_touched_;
  int touching_ = 0, touching_unskinned_ = 0;
  std::map<std::string, int> unskinned_links_;
};

}  // namespace somasim::plugins
