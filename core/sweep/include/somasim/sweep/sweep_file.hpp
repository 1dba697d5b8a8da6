#pragma once
/// @file
/// A sweep: many runs of one experiment file over values of its `--set` paths and seeds.
///
/// File format (all keys; unknown keys are errors; every error is "file:line:col: key 'k': ..."):
/// @code
///   sweep: NAME                   # required; letters, digits, '_' and '-'
///   experiment: ../base.yaml      # required; the base experiment, relative to this file
///   output: runs/sweeps/NAME      # optional output root, relative to the current directory
///                                 # (default runs/sweeps/NAME; `--out DIR` overrides it)
///   seeds: [1, 2, 3]              # optional: a list, or an inclusive range {from: 1, to: 3};
///                                 # default: one run per combination with the file's own seed
///   mode: grid                    # grid (default): every combination of the axes, first axis
///                                 # outermost; zip: the i-th value of every axis together
///   set:                          # optional fixed overrides for every run: PATH: VALUE
///     duration_s: 20
///   axes:                         # at least one (may be left out when `seeds` is given: a
///                                 # seed soak, one run per seed): a --set PATH and its values, as
///     nodes.thrower.params.offset: [-0.1, 0.0, 0.1]          # a list of YAML values,
///     nodes.filter.params.particles: {from: 100, to: 500, step: 200}  # a range (both ends
///     nodes.pps.params.ttc_max: {from: 1, to: 3, count: 5}   # included when hit), or count
///                                                            # values spread evenly
///   summary: {metric: KEY, against: PATH}   # optional: collect's default figure, KEY (a
///                                 # metric of metrics.json) against one of the axes' PATHs
/// @endcode
/// Runs are ordered by combination (in axis order) and, inside it, by seed. A range whose from,
/// to and step are integers gives integers; any other range gives numbers.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "somasim/source_location.hpp"

namespace somasim::sweep {

/// One value of an axis (or of a fixed `set:` entry), as YAML text for `--set PATH=VALUE`.
struct AxisValue {
  std::string text;  ///< one line of YAML (flow style for lists and maps)
  SourceLocation where;
};

/// One swept `--set` path and its values, in file order.
struct Axis {
  std::string path;  ///< dotted path, e.g. "nodes.thrower.params.offset"
  std::vector<AxisValue> values;
  SourceLocation where;  ///< the axis's key in the sweep file
};

enum class SweepMode { kGrid, kZip };

struct SweepSpec {
  std::filesystem::path file;  ///< the sweep file, as given (for messages)
  std::string name;
  std::filesystem::path experiment;  ///< absolute, normalised
  SourceLocation experiment_where;
  std::optional<std::filesystem::path> output;  ///< as written (relative to the current dir)
  std::vector<std::uint64_t> seeds;             ///< empty: the experiment's own seed
  SweepMode mode = SweepMode::kGrid;
  std::vector<Axis> fixed;  ///< `set:` entries, each with one value
  std::vector<Axis> axes;
  std::string summary_metric, summary_against;  ///< empty when there is no `summary:`
};

/// Reads and checks a sweep file (its own keys only; the runs are checked against the
/// experiment by resolve_jobs()). Throws InputError listing every problem, located.
SweepSpec load_sweep_file(const std::filesystem::path& file);

/// The same from text; `display_name` stands for the file in messages and `base_dir` resolves
/// the experiment path.
SweepSpec load_sweep_text(const std::string& yaml, const std::string& display_name,
                          const std::filesystem::path& base_dir);

/// The output root: `cli_out` when given, else the file's `output`, else runs/sweeps/NAME.
std::filesystem::path output_root(const SweepSpec& spec, const std::string& cli_out);

}  // namespace somasim::sweep
