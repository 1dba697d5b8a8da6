#pragma once
// The PPS evaluation's figures of merit from the per-presentation records: metrics.json keys
// and the per-presentation CSV.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "presentation_record.hpp"

namespace somasim::plugins {

/// {n, mean, median, min, max, p5, p95} of the finite values (percentiles: linear
/// interpolation between order statistics); n = 0: the statistics are null.
nlohmann::json summarize(std::vector<double> values);

/// The evaluation metrics (top-level keys, see plugins/pps_evaluation/README.md): over the
/// approach presentations `approaches`, `triggered_rate`, `skin_contact_rate` (any skin part
/// touched), `contact_rate` (the aimed part's skin touched), `object_contact_rate`,
/// `min_distance_m`, `trigger_distance_m`, `contact_time_s`; over static and receding ones
/// `false_trigger_rate`, `static_trigger_rate`, `receding_trigger_rate`; plus `per_part`
/// (approaches per aimed part) and `per_motion` breakdowns. Rates are shares in [0, 1] (null
/// when nothing was presented). Records never seen in the world are left out.
nlohmann::json evaluation_metrics(const std::vector<PresentationRecord>& records);

/// One row per record (header with units). InputError if the file cannot be written.
void write_presentations_csv(const std::filesystem::path& file,
                             const std::vector<PresentationRecord>& records);

}  // namespace somasim::plugins
