#pragma once
/// @file
/// Merging the JointCommands of several controllers into one (joint_command_mux).
#include <span>
#include <string>
#include <vector>

#include "somasim/name_table.hpp"
#include "somasim/robot/ports.hpp"

namespace somasim::control {

/// What happens when two inputs command the same dof (mode != kNone in both).
enum class MergeConflict {
  kLastWins,  ///< the later input in the list wins
  kError,     ///< merge_joint_commands() reports the conflict
};
inline constexpr NamedValue<MergeConflict> kMergeConflictNames[] = {
    {MergeConflict::kLastWins, "last_wins"}, {MergeConflict::kError, "error"}};
/// The conflict policies' names: "last_wins", "error".
constexpr std::span<const NamedValue<MergeConflict>> name_table(MergeConflict) {
  return kMergeConflictNames;
}

/// Merges `inputs` in order into `out` (resized to the inputs' dof count). Null inputs and
/// inputs with no dofs (a controller that has not run yet) are skipped; a dof no input commands
/// gets mode kNone. Returns "" on success, otherwise a description of the problem
/// ("inputs 0 and 2 both command dof 5", "input 1 has 12 dofs, expected 41"); `names` (same
/// size as inputs, optional) replaces the input indices in messages.
std::string merge_joint_commands(const std::vector<const JointCommand*>& inputs,
                                 MergeConflict conflict, JointCommand& out,
                                 const std::vector<std::string>& names = {});

}  // namespace somasim::control
