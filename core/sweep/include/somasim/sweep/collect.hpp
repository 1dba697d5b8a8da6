#pragma once
/// @file
/// Merging a sweep's runs into one table (sweep.csv) and a summary figure.
///
/// sweep.csv: one row per job in index order; columns `index`, `folder`, `seed`, one per axis
/// (header = its path), `status` (metrics.json's, or "missing"), then every number, string or
/// boolean of the runs' metrics.json under its flat name (metrics_layout.hpp: a node metric by
/// its own name, nested objects joined with '.', e.g. `per_part.left_forearm.thrown`; the union
/// over runs, sorted by name; empty where a run lacks it), and last the wall-clock columns (see
/// is_wall_clock_column()), which are the only ones that differ between two executions of the same
/// jobs.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace somasim::sweep {

/// The wall-clock-dependent columns, last in sweep.csv: `wall_time_s`, `real_time_factor`,
/// any metric whose name ends in `_ms`, and `host` (from manifest.json).
bool is_wall_clock_column(const std::string& name);

/// The table, as read from an output root.
struct SweepTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;   ///< cells as written to the csv (unquoted)
  std::vector<std::string> axes;                ///< axis paths (a subset of the header)
  std::string summary_metric, summary_against;  ///< the sweep file's `summary:`, if any
};

/// Reads DIR/sweep.json and every run's metrics.json and manifest.json. Throws InputError when
/// DIR is not a sweep output root.
SweepTable collect_table(const std::filesystem::path& root);

/// The table as CSV text (RFC 4180 quoting where a cell needs it).
std::string table_csv(const SweepTable& table);

/// Draws `metric` against axis `against`: mean ± sd over the completed runs sharing a value
/// (the seeds), one line per combination of the other axes' values, the y axis labelled with the
/// metric as a quantity and unit (metric_label), the x axis with `against_label` (e.g. the
/// parameter's doc and unit; default: the path's last component). Writes `png`. Throws
/// InputError (naming the nearest metric or the axes) when either is unknown, or no run has a
/// number for the metric. Returns the number of points drawn.
int draw_summary(const SweepTable& table, const std::string& metric, const std::string& against,
                 const std::filesystem::path& png, const std::string& against_label = "");
}  // namespace somasim::sweep
