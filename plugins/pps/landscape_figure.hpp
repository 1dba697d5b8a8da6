#pragma once
// Landscape figures of learned PPS maps: activation over D [cm] x TTC [s] with the Fig 8
// regression line.
#include <string>
#include <vector>

#include "somasim/plugin.hpp"
#include "somasim/pps/body_part_learner.hpp"

namespace somasim::plugins {

/// Draws figures/landscape_<part>_<id>[_<suffix>].png for the taxels listed in `taxel_ids`
/// (empty: the first four of the part).
void draw_landscapes(NodeContext& ctx, pps::BodyPartLearner& learner,
                     const std::vector<double>& taxel_ids, const std::string& suffix);

}  // namespace somasim::plugins
