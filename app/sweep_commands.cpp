#include "sweep_commands.hpp"

#include <algorithm>
#include <regex>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>
#include <CLI/CLI.hpp>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/sweep/child_process.hpp"
#include "somasim/sweep/collect.hpp"
#include "somasim/sweep/labels.hpp"
#include "somasim/sweep/run_folder.hpp"
#include "somasim/sweep/slurm_script.hpp"
#include "sweep_setup.hpp"

namespace somasim::app {
namespace fs = std::filesystem;

SweepSetup::SweepSetup(const CommonOptions& common, const SweepArgs& args, std::optional<int> only,
                       bool rewrite)
    : registry(PluginRegistry::default_search_path(common.plugin_path)),
      spec(sweep::load_sweep_file(args.file)) {
  jobs = sweep::expand_jobs(spec);
  root = sweep::output_root(spec, args.out);
  if (only) {
    if (*only < 0 || static_cast<std::size_t>(*only) >= jobs.size())
      throw InputError(
          fmt::format("--index {}: expected an index in [0, {}] (the sweep has {} runs)", *only,
                      jobs.size() - 1, jobs.size()));
    std::error_code ec;
    if (!fs::exists(root / "sweep.json", ec)) only.reset(), rewrite = true;
  }
  base = sweep::resolve_jobs(spec, jobs, registry, only);
  sweep::prepare_output_root(root, spec, base, jobs, rewrite);
}

SweepCommands::SweepCommands(CLI::App& app) {
  sweep_ = app.add_subcommand(
      "sweep",
      "Many runs of one experiment over values of --set paths and seeds (a sweep file, see "
      "README.md 'Sweeps'), on this machine or as a Slurm job array");
  sweep_->require_subcommand(1);
  auto out_option = [this](CLI::App* cmd) {
    cmd->add_option("--out", args_.out,
                    "Output folder (default: the sweep file's `output`, else runs/sweeps/NAME)");
  };
  expand_ = sweep_->add_subcommand(
      "expand", "Check every run and write DIR/jobs.tsv (index, run folder, seed, overrides)");
  expand_->add_option("sweep", args_.file, "Sweep file (YAML)")->required();
  out_option(expand_);

  run_ = sweep_->add_subcommand(
      "run",
      "Run every job here, N at a time, each as a child `somasim run`; completed runs are "
      "skipped, failed ones reported (exit 3) and re-run only with --retry-failed; Ctrl-C stops "
      "launching, lets the running ones flush and exits 130");
  run_->add_option("sweep", args_.file, "Sweep file (YAML)")->required();
  run_->add_option("-j,--jobs", args_.workers, "Concurrent runs (default 1)");
  run_->add_flag("--retry-failed", args_.retry_failed, "Run again the runs that failed before");
  out_option(run_);

  run_one_ = sweep_->add_subcommand(
      "run-one", "Run job I only (what each Slurm array task does); the same skip rules as run");
  run_one_->add_option("sweep", args_.file, "Sweep file (YAML)")->required();
  run_one_->add_option("--index", args_.index, "Job index (0-based, as in jobs.tsv)")->required();
  run_one_->add_flag("--retry-failed", args_.retry_failed, "Run it again if it failed before");
  out_option(run_one_);

  slurm_ = sweep_->add_subcommand(
      "slurm",
      "Write DIR/sweep.sbatch, a Slurm job array with one task per job (logs in DIR/logs), and "
      "print its path; --submit also submits it (sbatch --parsable) and prints the job id");
  slurm_->add_option("sweep", args_.file, "Sweep file (YAML)")->required();
  out_option(slurm_);
  slurm_->add_flag("--submit", args_.submit, "Submit the script with sbatch");
  slurm_->add_option("--array-throttle", args_.array_throttle,
                     "At most K tasks at once (--array=0-N%K)");
  slurm_->add_option("--partition", args_.partition, "Slurm partition (#SBATCH --partition)");
  slurm_->add_option("--time", args_.time, "Time limit per task, e.g. 01:30:00");
  slurm_
      ->add_option("--sbatch-arg", args_.sbatch_args,
                   "An extra #SBATCH line, e.g. --sbatch-arg=--mem=4G (repeatable)")
      ->allow_extra_args(false);

  collect_ = sweep_->add_subcommand(
      "collect",
      "Merge every run's metrics into DIR/sweep.csv (one row per run) and draw "
      "DIR/sweep_METRIC.png (METRIC against a swept value, mean +/- sd over seeds)");
  collect_->add_option("dir", args_.file, "The sweep's output folder")->required();
  collect_->add_option("--metric", args_.metric,
                       "Metric to draw (default: the sweep file's summary.metric)");
  collect_->add_option("--against", args_.against,
                       "Axis path to draw it against (default: summary.against, or the only axis)");
}

bool SweepCommands::selected() const {
  return sweep_ && *sweep_;
}

int SweepCommands::dispatch(const CommonOptions& common) const {
  if (*expand_) return cmd_sweep_expand(common, args_);
  if (*run_) return cmd_sweep_run(common, args_);
  if (*run_one_) return cmd_sweep_run_one(common, args_);
  if (*slurm_) return cmd_sweep_slurm(common, args_);
  if (*collect_) return cmd_sweep_collect(common, args_);
  return kExitBadInput;
}

int cmd_sweep_expand(const CommonOptions& common, const SweepArgs& args) {
  const SweepSetup setup(common, args, std::nullopt, true);
  fmt::print("{} runs: {}\n", setup.jobs.size(), (setup.root / "jobs.tsv").string());
  return kExitOk;
}

int cmd_sweep_slurm(const CommonOptions& common, const SweepArgs& args) {
  static const std::regex kSlurmTime(R"(^(\d+-)?\d+(:\d+){0,2}$)");
  if (!args.time.empty() && !std::regex_match(args.time, kSlurmTime))
    throw InputError("--time '" + args.time +
                     "': expected a Slurm time limit such as 01:30:00, 90 or 2-00:00:00");
  sweep::SlurmScriptSpec spec;
  spec.job_name = "check";
  spec.log_dir = "/check";
  spec.command = {"check"};
  spec.throttle = args.array_throttle;
  spec.partition = args.partition;
  spec.time = args.time;
  spec.extra = args.sbatch_args;
  sweep::slurm_script(spec);  // the options alone, before the sweep is set up
  const SweepSetup setup(common, args, std::nullopt, true);
  const fs::path root = fs::absolute(setup.root).lexically_normal();
  spec.job_name = setup.spec.name;
  spec.tasks = setup.jobs.size();
  spec.log_dir = (root / "logs").string();
  spec.comments = {
      fmt::format("Written by `somasim sweep slurm` for sweep '{}' ({} runs of {}).",
                  setup.spec.name, spec.tasks, setup.spec.experiment.string()),
      "Each array task runs one job; completed runs are skipped, so resubmitting resumes."};
  spec.command = {sweep::self_executable().string()};
  for (const auto& p : common.plugin_path) {
    spec.command.emplace_back("--plugin-path");
    spec.command.push_back(fs::absolute(p).string());
  }
  for (const std::string& w : {std::string("sweep"), std::string("run-one"),
                               fs::absolute(setup.spec.file).lexically_normal().string(),
                               std::string("--out"), root.string()})
    spec.command.push_back(w);
  const std::string script = sweep::slurm_script(spec);
  const fs::path file = root / "sweep.sbatch";
  sweep::write_file_atomically(file, script);
  fs::permissions(file, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  fmt::print("{}\n", file.string());
  if (!args.submit) return kExitOk;
  std::fflush(stdout);
  const fs::path sbatch = sweep::find_on_path("sbatch");
  if (sbatch.empty()) {
    fmt::print(stderr,
               "error: sbatch not found on PATH: install slurm-client or run on a Slurm login "
               "node; the script is at {}\n",
               file.string());
    return kExitBadInput;
  }
  std::string out, err;
  const sweep::ChildExit exit =
      sweep::run_capture({sbatch.string(), "--parsable", file.string()}, out, err);
  if (exit.code != 0) {
    fmt::print(stderr, "error: sbatch failed ({}): {}", exit.str(), err);
    return kExitRunFailed;
  }
  const std::string id = out.substr(0, out.find_first_of(";\n"));
  fmt::print("{}\n", id);
  return kExitOk;
}

namespace {

// The label of a swept path from the parameter's declaration ("offset [m]: ..."): the plugin of
// node N in the first run's resolved experiment, its parameter P (paths nodes.N.params.P).
// Empty when the path is not a node parameter or the run or plugin cannot be read.
std::string swept_parameter_label(const CommonOptions& common, const fs::path& root,
                                  const sweep::SweepTable& table, const std::string& path) {
  const std::vector<std::string> parts = [&] {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (std::size_t dot; (dot = path.find('.', start)) != std::string::npos; start = dot + 1)
      out.push_back(path.substr(start, dot - start));
    out.push_back(path.substr(start));
    return out;
  }();
  if (parts.size() != 4 || parts[0] != "nodes" || parts[2] != "params" || table.rows.empty())
    return "";
  const auto folder_col = static_cast<std::size_t>(
      std::find(table.header.begin(), table.header.end(), "folder") - table.header.begin());
  if (folder_col >= table.header.size()) return "";
  try {
    const fs::path resolved = root / table.rows.front()[folder_col] / "experiment.resolved.yaml";
    if (!fs::is_regular_file(resolved) || fs::file_size(resolved) > (std::uintmax_t{2} << 20))
      return "";
    const YAML::Node plugin = YAML::LoadFile(resolved.string())["nodes"][parts[1]]["plugin"];
    if (!plugin.IsScalar()) return "";
    PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
    const PluginSpec* spec = registry.find(plugin.Scalar());
    if (!spec) return "";
    for (const auto& p : spec->params())
      if (p.name == parts[3]) return sweep::parameter_label(path, p.doc, p.unit);
  } catch (const std::exception&) {  // a label is not worth failing the table for
  }
  return "";
}

}  // namespace

int cmd_sweep_collect(const CommonOptions& common, const SweepArgs& args) {
  const fs::path root = args.file;
  const sweep::SweepTable table = sweep::collect_table(root);
  std::string metric = args.metric.empty() ? table.summary_metric : args.metric;
  std::string against = args.against;
  if (against.empty()) against = table.summary_against;
  if (against.empty() && table.axes.size() == 1) against = table.axes.front();
  if (metric.empty() && !args.against.empty())
    throw InputError("--against '" + args.against + "': name the metric to draw with --metric");
  if (!metric.empty() && against.empty())
    throw InputError("--metric '" + metric +
                     "': name the axis to draw it against with --against (one of: " +
                     join_names(table.axes) + ")");
  // Check the figure's request before writing anything.
  std::string file_metric = metric;
  for (char& c : file_metric)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') c = '_';
  const fs::path png = root / ("sweep_" + file_metric + ".png");
  std::size_t completed = 0;
  const auto status_col = static_cast<std::size_t>(
      std::find(table.header.begin(), table.header.end(), "status") - table.header.begin());
  for (const auto& row : table.rows) completed += row[status_col] == "completed";
  int points = 0;
  if (!metric.empty())
    points = sweep::draw_summary(table, metric, against, png,
                                 swept_parameter_label(common, root, table, against));
  sweep::write_file_atomically(root / "sweep.csv", sweep::table_csv(table));
  fmt::print("{}: {} runs ({} completed), {} columns\n", (root / "sweep.csv").string(),
             table.rows.size(), completed, table.header.size());
  if (!metric.empty())
    fmt::print("{}: {} against {}, {} points\n", png.string(), metric, against, points);
  return kExitOk;
}

}  // namespace somasim::app
