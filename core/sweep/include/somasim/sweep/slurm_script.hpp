#pragma once
/// @file
/// The Slurm batch script of a sweep (`somasim sweep slurm`): a job array whose tasks each run
/// one job. Every value that reaches the script is checked or quoted, so that nothing a user
/// types (a partition, an output folder, an experiment's file name) can become a command:
/// - `#SBATCH` values (job name, log paths, partition, time) may hold only letters, digits and
///   `. _ / % + , : = @ ~ -` (what Slurm's names, times and paths need); anything else is an
///   InputError naming the value and the character;
/// - extra `#SBATCH` options must each be one line starting with '-' without control characters;
/// - comment text has its control characters replaced by '?';
/// - the command's words are single-quoted for bash, except the array task id variable.
#include <cstddef>
#include <string>
#include <vector>

namespace somasim::sweep {

struct SlurmScriptSpec {
  std::string job_name;               ///< --job-name
  std::size_t tasks = 1;              ///< --array=0-(tasks-1); >= 1
  int throttle = 0;                   ///< at most this many tasks at once (%K); 0: no limit
  std::string log_dir;                ///< absolute folder of the tasks' stdout/stderr files
  std::string partition;              ///< --partition; "" for the cluster's default
  std::string time;                   ///< --time; "" for the partition's default
  std::vector<std::string> extra;     ///< further #SBATCH options, e.g. "--mem=4G"
  std::vector<std::string> comments;  ///< lines of the comment below the directives
  /// The task's command: `exec` of these words (each quoted), followed by the words
  /// `--index "$SLURM_ARRAY_TASK_ID"` when `pass_task_index`.
  std::vector<std::string> command;
  bool pass_task_index = true;
};

/// The script's text (bash, directives first). Throws somasim::InputError for a value the
/// file comment refuses, naming what it is ("--partition 'a b': ...").
std::string slurm_script(const SlurmScriptSpec& spec);

/// `s` as one single-quoted bash word.
std::string shell_quote(const std::string& s);

}  // namespace somasim::sweep
