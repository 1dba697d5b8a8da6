#pragma once
/// @file
/// What a sweep keeps on disk, and what a run folder says about its run.
///
/// Output root (DIR):
///   sweep.json      the sweep's manifest: sweep and base experiment (name, hash), axes, jobs
///   jobs.tsv        the job list (jobs_tsv())
///   runs/NNNN/      one run folder per job: the run's own outputs plus manifest.json
///   logs/           each run's stdout/stderr (local: NNNN.log; Slurm: JOBID_TASK.out/.err)
///   sweep.csv, sweep_METRIC.png   written by collect
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "somasim/sweep/jobs.hpp"

namespace somasim::sweep {

/// What is found in a job's run folder.
enum class RunState {
  kCompleted,  ///< metrics.json says completed and the resolved experiment matches: skip
  kFailed,     ///< the manifest records a failure of this very job: re-run only on request
  kRedo,       ///< missing, interrupted, half-written or of another experiment: run it
};

/// Decides from metrics.json, experiment.resolved.yaml and manifest.json of `run_dir`.
RunState run_state(const std::filesystem::path& run_dir, const Job& job);

/// The sweep manifest (sweep.json) for `spec`, `base` and `jobs`.
nlohmann::ordered_json sweep_manifest(const SweepSpec& spec, const BaseExperiment& base,
                                      const std::vector<Job>& jobs);

/// Makes `root` the output root of this sweep: creates it and writes sweep.json and jobs.tsv
/// (each atomically, through a temporary file and a rename, so concurrent array tasks never see
/// half a file). Throws InputError when `root` holds runs of another base experiment (its
/// sweep.json names another experiment or hash), or holds files but no sweep.json.
/// `rewrite`: false leaves existing, matching files alone (what a Slurm array task does).
void prepare_output_root(const std::filesystem::path& root, const SweepSpec& spec,
                         const BaseExperiment& base, const std::vector<Job>& jobs, bool rewrite);

/// Reads DIR/sweep.json. Throws InputError when it is missing or malformed.
nlohmann::json read_sweep_manifest(const std::filesystem::path& root);

/// Throws InputError when a job's run folder `root / relative` (or a folder on the way to it
/// below `root`) is a symbolic link: the sweep empties run folders before each run and must not
/// delete through a link someone placed there. Nothing is deleted.
void check_no_links_below(const std::filesystem::path& root, const std::string& relative);

/// Writes `text` to `file` through `file.tmp.PID` and a rename. Throws InputError on failure.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

/// The somasim git revision at configure time (`git rev-parse --short HEAD`), or "unknown".
const char* git_revision();

}  // namespace somasim::sweep
