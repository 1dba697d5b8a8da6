#pragma once
// Runs a shipped experiment config into a fresh folder and reads its outputs (for tests).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "somasim/experiment.hpp"
#include "somasim/runner.hpp"

namespace somasim::testing {

struct ExperimentRun {
  std::filesystem::path dir;
  RunReport report;
  nlohmann::json metrics;  ///< metrics.json as written
  /// The run keys and every node metric under its flat name (somasim/metrics_layout.hpp),
  /// values whole: one object to look metrics up by name.
  nlohmann::json flat;

  /// A metric by its flat name (somasim/metrics_layout.hpp); null when the run has none.
  nlohmann::json metric(std::string_view name) const;
};

/// Runs `configs/<name>.yaml` with `overrides` into a fresh temporary folder `tag`.
ExperimentRun run_config(const std::string& name, const std::vector<Override>& overrides = {},
                         const std::string& tag = "");

/// The content of a file (empty if missing).
std::string read_file(const std::filesystem::path& file);

/// The shared reference-data folder (SOMASIM_SHARED_DIR or <source>/../shared), or "" if absent.
std::filesystem::path shared_dir();

}  // namespace somasim::testing
