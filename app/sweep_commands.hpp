#pragma once
// `somasim sweep expand | run | run-one | slurm | collect`: many runs of one experiment, on this
// machine or as a Slurm job array. See core/sweep/include/somasim/sweep/sweep_file.hpp for the
// sweep file and run_folder.hpp for what lands in the output folder.
#include <string>
#include <vector>

#include "commands.hpp"

namespace CLI {
class App;
}

namespace somasim::app {

struct SweepArgs {
  std::string file;  ///< the sweep file (collect: the output folder)
  std::string out;   ///< --out: the output root (default: the file's `output`)
  int workers = 1;   ///< run -j
  bool retry_failed = false;
  int index = -1;  ///< run-one --index
  bool submit = false;
  int array_throttle = 0;  ///< 0: no %K
  std::string partition, time;
  std::vector<std::string> sbatch_args;
  std::string metric, against;  ///< collect's figure
};

/// Adds `sweep` and its verbs to `app`; dispatch() runs the one the command line chose.
class SweepCommands {
 public:
  explicit SweepCommands(CLI::App& app);
  bool selected() const;
  int dispatch(const CommonOptions& common) const;

 private:
  SweepArgs args_;
  CLI::App* sweep_ = nullptr;
  CLI::App* expand_ = nullptr;
  CLI::App* run_ = nullptr;
  CLI::App* run_one_ = nullptr;
  CLI::App* slurm_ = nullptr;
  CLI::App* collect_ = nullptr;
};

int cmd_sweep_expand(const CommonOptions& common, const SweepArgs& args);
/// Runs every job with args.workers concurrent child processes; exit 0, 3 (a run failed) or 130.
int cmd_sweep_run(const CommonOptions& common, const SweepArgs& args);
/// Runs job args.index (what a Slurm array task calls); the same skip rules as run.
int cmd_sweep_run_one(const CommonOptions& common, const SweepArgs& args);
/// Writes DIR/sweep.sbatch (stdout: its path; with --submit, then the job id). Exit 2 when
/// sbatch is not on PATH.
int cmd_sweep_slurm(const CommonOptions& common, const SweepArgs& args);
/// Writes DIR/sweep.csv and, for a metric, DIR/sweep_METRIC.png.
int cmd_sweep_collect(const CommonOptions& common, const SweepArgs& args);

}  // namespace somasim::app
