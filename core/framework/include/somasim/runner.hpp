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

/// Runs `experiment` to completion (or failure or SIGINT) and writes the run folder.
RunReport run_experiment(const Experiment& experiment, const RunOptions& options);

}  // namespace somasim
