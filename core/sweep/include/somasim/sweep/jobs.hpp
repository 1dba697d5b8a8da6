#pragma once
/// @file
/// The job list of a sweep: one run per combination of axis values and seed, each checked by
/// loading the base experiment with its overrides through the normal experiment loader.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "somasim/experiment.hpp"
#include "somasim/sweep/sweep_file.hpp"

namespace somasim {
class PluginRegistry;
}

namespace somasim::sweep {

/// One run of a sweep.
struct Job {
  int index = 0;                         ///< 0-based position in the job list
  std::string folder;                    ///< run folder, relative to the output root
  std::optional<std::uint64_t> seed;     ///< --seed; empty: the experiment's own
  std::vector<Override> overrides;       ///< fixed `set:` entries, then one per axis
  std::vector<std::string> axis_values;  ///< the value of each axis (same order as the axes)
  std::vector<SourceLocation> origins;   ///< where each axis value was written
  std::uint64_t resolved_seed = 0;       ///< filled by resolve_jobs()
  std::string resolved_hash;             ///< filled by resolve_jobs(): hash of the resolved yaml
};

/// Expands the axes and seeds into jobs (no experiment is loaded). Throws InputError, located
/// at the axes, when zipped axes differ in length.
std::vector<Job> expand_jobs(const SweepSpec& spec);

/// The experiment the base file gives without overrides (for the output root's manifest).
struct BaseExperiment {
  std::string name;
  std::string hash;  ///< resolved_hash() of the base experiment
};

/// Loads the base experiment, then each job's experiment with its overrides and seed, filling
/// `resolved_seed` and `resolved_hash`. `only`: check just that job (and the base). A job the
/// loader rejects throws InputError: the sweep file's location of the value (or of the
/// `experiment:` key) and axis, then the loader's own message (with its "did you mean").
BaseExperiment resolve_jobs(const SweepSpec& spec, std::vector<Job>& jobs, PluginRegistry& registry,
                            std::optional<int> only = std::nullopt);

/// Loads one job's experiment (as resolve_jobs() does; the job must be resolvable).
Experiment load_job_experiment(const SweepSpec& spec, const Job& job, PluginRegistry& registry);

/// jobs.tsv: a header line, then per job: index, folder, seed, then one `path=value` per override,
/// separated by tabs.
std::string jobs_tsv(const std::vector<Job>& jobs);

}  // namespace somasim::sweep
