#pragma once
// The pps_learner's metrics: sample counts, estimated systematic offsets (ridge end = best
// estimator, Fig 8 = the paper's) per taxel and per body part, and, when the true offsets are
// wired, their errors.
#include <vector>

#include "learner_part.hpp"
#include "somasim/plugin.hpp"
#include "somasim/port_types.hpp"

namespace somasim::plugins {

/// Reports every metric of the learner (keys in README.md, pps_learner). Taxels with fewer than
/// `min_samples` learned samples are left out of the offset statistics. `true_offsets` (null:
/// unwired) is matched to the taxels by label "part/id"; NaN or missing values are left out.
void report_learning(NodeContext& ctx, std::vector<LearnerPart>& parts, int min_samples,
                     const TaxelValues* true_offsets);

}  // namespace somasim::plugins
