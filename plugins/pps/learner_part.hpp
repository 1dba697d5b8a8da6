#pragma once
// One body part of a pps_learner: its learner and where its taxels are in the ports.
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/learned_state.hpp"

namespace somasim::plugins {

struct LearnerPart {
  std::string name;  ///< skin part name, as in the 'taxels' input
  /// Created in configure() from a loaded file, or on the first step from the 'taxels' input.
  std::unique_ptr<pps::BodyPartLearner> learner;
  /// Loaded from a file without taxel geometry (`.ini`): the learner is made on the first step,
  /// with the geometry of the 'taxels' input (matched by taxel id).
  std::unique_ptr<pps::LearnedState> needs_geometry;
  /// Index of the part in the 'taxels' input's parts (found by name once, re-checked per tick).
  std::size_t input_index = std::numeric_limits<std::size_t>::max();
  std::size_t first = 0;              ///< index of its first taxel in the activations output
  std::vector<pps::TaxelPose> poses;  ///< taxel poses in the root frame, current tick
  std::size_t events = 0;             ///< contact events learned from
  bool event_before_now = false;      ///< scratch of step(): a new event earlier than now
};

}  // namespace somasim::plugins
