#pragma once
// The `somasim` subcommands. Each returns the process exit code (see kExit*).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace somasim::app {

/// Exit codes (documented in README.md and `somasim --help`).
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 2;   ///< bad experiment, parameters, plugin libraries, usage
inline constexpr int kExitRunFailed = 3;  ///< the run started but a node failed
inline constexpr int kExitInterrupted = 130;  ///< SIGINT/SIGTERM; outputs were flushed

struct CommonOptions {
  std::vector<std::filesystem::path> plugin_path;
};

struct RunArgs {
  std::string file;
  std::vector<std::string> sets;  ///< "path=value"
  std::string seed;               ///< "": the experiment's own
  std::string out;
  bool overwrite = false;  ///< an existing run folder is emptied first (else refused)
  bool quiet = false;
  double progress_every_s = 60.0;  ///< without a terminal: a progress log line this often [s]
};

int cmd_run(const CommonOptions& common, const RunArgs& args);
int cmd_validate(const CommonOptions& common, const std::string& file,
                 const std::vector<std::string>& sets);
/// Lists the plugins found, then each library and whether it was dlopen'ed to list it.
int cmd_plugins(const CommonOptions& common);
/// Writes `<library>.index` for each library (opens each one).
int cmd_index_plugins(const std::vector<std::string>& libraries);
int cmd_describe(const CommonOptions& common, const std::string& name);
/// Reads a learned map (.json or .ini) and writes it in the format `output`'s extension names.
int cmd_pps_convert(const std::string& input, const std::string& output);
int cmd_graph(const CommonOptions& common, const std::string& file);

}  // namespace somasim::app
