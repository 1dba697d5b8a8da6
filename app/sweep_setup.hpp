#pragma once
// What every `somasim sweep` verb but collect starts with: the sweep file read, its jobs
// expanded and checked with the experiment loader, and the output root prepared.
#include <filesystem>
#include <optional>
#include <vector>

#include "somasim/plugin_registry.hpp"
#include "somasim/sweep/jobs.hpp"
#include "somasim/sweep/sweep_file.hpp"
#include "sweep_commands.hpp"

namespace somasim::app {

struct SweepSetup {
  /// `only`: check just that job (a Slurm array task), unless the output root has no sweep.json
  /// yet. `rewrite`: write sweep.json and jobs.tsv even when they exist. Throws InputError.
  SweepSetup(const CommonOptions& common, const SweepArgs& args, std::optional<int> only,
             bool rewrite);

  PluginRegistry registry;
  sweep::SweepSpec spec;
  std::vector<sweep::Job> jobs;
  sweep::BaseExperiment base;
  std::filesystem::path root;  ///< the output root
};

}  // namespace somasim::app
