#pragma once
// pps_learner's `offset_groups`: named sets of taxels whose offsets are also reported together
// (the paper's Fig 8 groups: inner forearm, outer forearm, palm).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace somasim::plugins {

/// Taxels of one body part, optionally only those whose outward normal (link frame) has a
/// positive component along `side`.
struct OffsetGroup {
  std::string name;
  std::string part;                     ///< skin part name
  std::optional<Eigen::Vector3d> side;  ///< unit axis of the part's link frame; none = all

  bool contains(const std::string& taxel_part, const Eigen::Vector3d& normal_link) const {
    return taxel_part == part && (!side || normal_link.dot(*side) > 0.0);
  }
};

/// Parses "name: part [±x|±y|±z], name: part ..." (empty text: no groups). `parts` are the
/// learner's body parts. InputError naming the entry and what was expected.
std::vector<OffsetGroup> parse_offset_groups(const std::string& text,
                                             const std::vector<std::string>& parts);

}  // namespace somasim::plugins
