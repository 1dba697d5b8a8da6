#pragma once
/// @file
/// The layout of a run's metrics.json, and the flat names that tables and tests use.
///
/// metrics.json holds the run's own keys at the top level (kRunMetricKeys: experiment, status,
/// error, stop_reason, seed, sim_time_s, wall_time_s, real_time_factor, versions; pid while
/// running) and one section per node under `nodes` (`nodes.NODE.METRIC`, each node's metrics as the
/// node reported them, nested objects included). Nothing is written twice.
///
/// A node metric's *flat name* is its own name when no other node reports that name and it is not
/// a run key, and `NODE.METRIC` otherwise. Flattening goes on into nested objects, joining keys
/// with '.': `per_part.left_forearm.thrown`. sweep.csv's columns and `find_metric` use these names.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace somasim {

/// The run's own top-level keys of metrics.json, in the order they are written (`pid` and
/// `host` only while the run is running; `recovered` after `somasim recover`).
inline constexpr std::array<std::string_view, 12> kRunMetricKeys = {
    "experiment",  "status",           "error",    "stop_reason", "seed", "sim_time_s",
    "wall_time_s", "real_time_factor", "versions", "pid",         "host", "recovered"};

/// Every node metric (first level of each `nodes` section) under its flat name, in node order,
/// with its value as reported (objects and lists kept whole).
std::vector<std::pair<std::string, nlohmann::json>> node_metrics_by_flat_name(
    const nlohmann::json& metrics);

/// A metric by name: a run key, a node metric's flat name, or either followed by '.'-joined keys
/// into nested objects (`per_part.left_forearm.thrown`). nullopt when there is none.
std::optional<nlohmann::json> find_metric(const nlohmann::json& metrics, std::string_view name);

/// Every scalar (number, string, boolean, null) of metrics.json under its flat name: run keys
/// first (versions as `versions.somasim`, ...), then the node metrics, nested objects flattened
/// with '.'. Lists are not flattened (they are left out).
std::vector<std::pair<std::string, nlohmann::json>> flatten_metrics(const nlohmann::json& metrics);

}  // namespace somasim
