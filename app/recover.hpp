#pragma once
// `somasim recover RUN_FOLDER`: what a killed run (SIGKILL, power loss, out of memory) left is
// made consistent and says so: a CSV's partial last row is trimmed, and metrics.json, which still
// says `running`, says `killed` and lists what was trimmed.
#include <filesystem>
#include <string>
#include <vector>

namespace somasim::app {

/// What recover_run_folder did.
struct RecoveryReport {
  std::vector<std::string> trimmed;  ///< "FILE: N bytes of a partial last row removed"
};

/// Recovers `dir`: refused (InputError) unless its metrics.json says `running`, its process
/// (`pid`) is gone and no other somasim holds the folder. Every CSV file under it (recorders'
/// CSVs, image indexes) that does not end with a newline is cut back to its last complete row;
/// metrics.json is rewritten with status `killed`. Writes nothing outside `dir`, follows no links.
RecoveryReport recover_run_folder(const std::filesystem::path& dir);

int cmd_recover(const std::string& dir);

}  // namespace somasim::app
