#pragma once
// The pps_learner's metrics: sample counts, estimated systematic offsets (floor = best
// estimator, ridge end, Fig 8 = the paper's) per taxel and per body part, and, when the true
// offsets are wired, their errors.
#include <vector>

#include "learner_part.hpp"
#include "offset_groups.hpp"
#include "somasim/plugin.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

/// Reports every metric of the learner. "Counted" taxels have >= `min_samples` learned samples;
/// offsets [m] are the perceived D at contact: floor = estimate_offset_floor (best: it locates
/// the radial D the truth defines), ridge = estimate_offset_ridge (the contact's distance along
/// the normal), paper = estimate_offset (Fig 8; none for the distance-only model). Estimates are
/// computed for counted taxels only (null for the others).
/// - `events`, `samples`, `positive_samples`, `negative_samples`, `negative_d_share`: all parts;
///   `per_part` = {part: the same per part, plus `taxels`}.
/// - `offset_floor_m`, `offset_ridge_m`, `offset_estimate_m`: mean floor / ridge / paper offset
///   over counted taxels of all parts; `offset_mean_m` (floor), `offset_mean_ridge_m`,
///   `offset_mean_paper_m` = {part: the same per part} (null: none).
/// - `taxels` = {id (one part) or "part/id": {samples, offset_floor_m, offset_ridge_m,
///   offset_estimate_m, true_offset_m}}.
/// With `true_offsets` (null: unwired; matched by label "part/id", NaN or missing = unknown):
/// - `true_offset_mean_m` = {part: mean true offset over counted taxels with a known one};
/// - `offset_error_max_m`, `offset_error_mean_m` (floor), `offset_error_max_ridge_m`,
///   `offset_error_mean_ridge_m` and `offset_error_max_paper_m`, `offset_error_mean_paper_m`:
///   max / mean of |estimate - true| over counted taxels with a known true offset and an
///   estimate; `offset_taxels_evaluated`: counted taxels with a known true offset;
///   `offset_taxels_without_estimate` = {floor, ridge, paper}: of those, how many had none;
///   per part: `offset_taxels_evaluated` and the six error keys.
/// With `groups`: `offset_groups` = {group: {taxels (counted), offset_mean_m (contact),
/// offset_mean_paper_m, and with true_offsets true_offset_mean_m, offset_error_max_m,
/// offset_error_mean_m (contact), offset_taxels_evaluated}}.
void report_learning(NodeContext& ctx, std::vector<LearnerPart>& parts, int min_samples,
                     const TaxelValues* true_offsets, const std::vector<OffsetGroup>& groups = {});

}  // namespace somasim::plugins
