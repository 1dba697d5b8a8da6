#pragma once
/// @file
/// Learned PPS state of one body part, as saved/loaded/imported (see map_io.hpp, ini_import.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "somasim/pps/body_part_learner.hpp"
#include "somasim/pps/grid.hpp"
#include "somasim/pps/stimulus.hpp"
#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

struct LearnedTaxel {
  int id = 0;
  TaxelPose pose_link;               ///< position [m] and normal in the link frame
  std::vector<TaxelMap::Count> pos;  ///< D-major, grid.size() entries
  std::vector<TaxelMap::Count> neg;
  /// The `contact` offset estimator's evidence (BodyPartLearner::record_contact_offset): sum of
  /// the perceived D at contact [m] over `contact_events` contacts.
  double contact_d_sum = 0.0;
  std::uint32_t contact_events = 0;
};

struct LearnedState {
  std::string body_part;
  PpsModel model = PpsModel::kDTtc;
  /// The maps' grid (for the distance-only model: distance_only_grid(), one TTC bin).
  GridSpec grid;
  ParzenSpec parzen;
  std::vector<LearnedTaxel> taxels;
};

/// Snapshot of a learner's maps.
LearnedState learned_state(const BodyPartLearner& learner);

/// A learner restored from `state`; model, grid and Parzen variant come from the state, the rest of
/// `params` (RF, TTC definition, buffer) is used as given.
BodyPartLearner make_learner(const LearnedState& state, LearnerParams params);

/// The map of one learned taxel.
TaxelMap make_map(const LearnedState& state, const LearnedTaxel& taxel);

}  // namespace somasim::pps
