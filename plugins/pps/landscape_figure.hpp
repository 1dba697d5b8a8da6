#pragma once
// Landscape figures of learned PPS maps: activation over D [cm] x TTC [s] with the Fig 8
// regression line, the floor estimate and (when known) the true offset.
#include <string>
#include <vector>

#include "somasim/plugin.hpp"
#include "somasim/pps/body_part_learner.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

/// Draws figures/landscape_<part>_<id>[_<suffix>].png for the taxels listed in `taxel_ids`
/// (empty: the first four of the part). `true_offsets` (may be null): the offsets the taxels
/// should show, by label "part/id" [m]; a finite one is drawn as a vertical line.
void draw_landscapes(NodeContext& ctx, pps::BodyPartLearner& learner,
                     const std::vector<double>& taxel_ids, const std::string& suffix,
                     const TaxelValues* true_offsets = nullptr);

}  // namespace somasim::plugins
