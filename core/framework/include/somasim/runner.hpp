#pragma once
/// @file
/// Running an experiment into a run folder:
///   experiment.resolved.yaml, log.txt, metrics.json, NODE.PORT.csv per recorded port,
///   figures/*.png and plugin artefacts. Outputs are flushed whatever happens.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "somasim/experiment.hpp"

namespace somasim {

enum class RunStatus { Completed, BadInput, Failed, Interrupted };

/// "completed", "bad_input", "failed", "interrupted" (the `status` of metrics.json).
const char* run_status_name(RunStatus status);

struct RunOptions {
  std::filesystem::path out_dir;  ///< created if missing
  bool quiet = false;             ///< no progress and only warnings on stderr
  bool progress = true;           ///< progress line on stderr (only if stderr is a terminal)
  /// When stderr is not a terminal: a progress line in the log every this many seconds of wall
  /// time (0: none). Not with `quiet`.
  double progress_every_s = 60.0;
};

struct RunReport {
  RunStatus status = RunStatus::Completed;
  std::string error;               ///< why the run failed (empty when completed)
  std::string stop_reason;         ///< why it ended ("duration reached", a node's reason, ...)
  nlohmann::ordered_json metrics;  ///< the content written to metrics.json
};

/// Writes metrics.json (or any JSON file of a run folder) so that a reader or a crash sees the old
/// file or the new one: a temporary file beside it (not through a link), fsync'ed, renamed over
/// it, and the folder fsync'ed. Throws std::runtime_error naming the file when it cannot.
void write_metrics_file(const std::filesystem::path& file, const nlohmann::ordered_json& metrics);

/// This machine's host name ("" if unknown), recorded with the pid of a running run.
std::string host_name();

/// Runs `experiment` to completion (or failure or SIGINT) and writes the run folder.
RunReport run_experiment(const Experiment& experiment, const RunOptions& options);

}  // namespace somasim
