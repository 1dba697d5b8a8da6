// Expanding a sweep into jobs, and checking every job with the experiment loader.
#include "somasim/sweep/jobs.hpp"

#include <fmt/format.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/sweep/hash.hpp"

namespace somasim::sweep {

namespace {

// Beyond any allocation a cluster grants; keeps a typo from exhausting memory.
// A sweep's size: runs, and overrides over all runs (each a path, a value and where it was
// written), so that expanding the largest accepted sweep takes seconds and little memory.
constexpr std::size_t kMaxJobs = 100000;
constexpr std::size_t kMaxOverrides = 2000000;

std::string folder_name(int index, std::size_t count) {
  int width = 4;
  for (std::size_t n = 10000; n < count; n *= 10) ++width;
  return fmt::format("runs/{:0{}}", index, width);
}

}  // namespace

std::vector<Job> expand_jobs(const SweepSpec& spec) {
  // Each combination: one value index per axis.
  std::vector<std::vector<std::size_t>> combos;
  // Where a size error points: the first axis, or the experiment key of a seed soak.
  const SourceLocation& anchor =
      spec.axes.empty() ? spec.experiment_where : spec.axes.front().where;
  if (spec.mode == SweepMode::kZip && !spec.axes.empty()) {
    Diagnostics diags;
    const Axis& first = spec.axes.front();
    for (const Axis& a : spec.axes)
      if (a.values.size() != first.values.size())
        diags.add(a.where, "", "axes." + a.path,
                  fmt::format("zipped axes need the same number of values: '{}' has {} (at {}), "
                              "this one has {}",
                              first.path, first.values.size(), first.where.str(), a.values.size()));
    diags.throw_if_any();
    for (std::size_t i = 0; i < first.values.size(); ++i) combos.emplace_back(spec.axes.size(), i);
  } else {
    double total = 1;
    for (const Axis& a : spec.axes) total *= static_cast<double>(a.values.size());
    if (total * static_cast<double>(std::max<std::size_t>(spec.seeds.size(), 1)) >
        static_cast<double>(kMaxJobs))
      throw InputError(
          fmt::format("{}: key 'axes': the grid has more than {} runs", anchor.str(), kMaxJobs));
    std::vector<std::size_t> idx(spec.axes.size(), 0);
    while (true) {
      combos.push_back(idx);
      std::size_t k = idx.size();  // odometer, last axis fastest
      while (k > 0 && ++idx[k - 1] == spec.axes[k - 1].values.size()) idx[--k] = 0;
      if (k == 0) break;
    }
  }
  const std::size_t seeds = std::max<std::size_t>(spec.seeds.size(), 1);
  if (combos.size() * seeds > kMaxJobs)
    throw InputError(
        fmt::format("{}: key 'seeds': the sweep has more than {} runs", anchor.str(), kMaxJobs));
  const std::size_t per_run = spec.axes.size() + spec.fixed.size();
  if (combos.size() * seeds * per_run > kMaxOverrides)
    throw InputError(fmt::format(
        "{}: key 'axes': {} runs of {} overrides each are more than {} overrides in all; split "
        "the sweep",
        anchor.str(), combos.size() * seeds, per_run, kMaxOverrides));
  std::vector<Job> jobs;
  const std::size_t count = combos.size() * seeds;
  for (const auto& combo : combos)
    for (std::size_t s = 0; s < seeds; ++s) {
      Job job;
      job.index = static_cast<int>(jobs.size());
      job.folder = folder_name(job.index, count);
      if (!spec.seeds.empty()) job.seed = spec.seeds[s];
      for (const Axis& f : spec.fixed) job.overrides.push_back({f.path, f.values.front().text});
      for (std::size_t a = 0; a < spec.axes.size(); ++a) {
        const AxisValue& v = spec.axes[a].values[combo[a]];
        job.overrides.push_back({spec.axes[a].path, v.text});
        job.axis_values.push_back(v.text);
        job.origins.push_back(v.where);
      }
      jobs.push_back(std::move(job));
    }
  return jobs;
}

namespace {

LoadOptions job_options(const Job& job) {
  LoadOptions options;
  options.overrides = job.overrides;
  options.seed = job.seed;
  return options;
}

// The loader's message, prefixed with the sweep file's location of what caused it: the axis
// value or fixed override it names, else the `experiment:` key.
// The loader names an override as "--set 'PATH=VALUE'" (a bad path) or "--set PATH=VALUE" (a
// bad value).
bool names_override(const std::string& msg, const std::string& path) {
  return msg.find("--set '" + path + "=") != std::string::npos ||
         msg.find("--set " + path + "=") != std::string::npos;
}

[[noreturn]] void rethrow_located(const SweepSpec& spec, const Job* job, const InputError& e) {
  const std::string msg = e.what();
  if (job) {
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
      if (names_override(msg, spec.axes[a].path))
        throw InputError(
            fmt::format("{}: key 'axes.{}': {}", job->origins[a].str(), spec.axes[a].path, msg));
    for (const Axis& f : spec.fixed)
      if (names_override(msg, f.path))
        throw InputError(
            fmt::format("{}: key 'set.{}': {}", f.values.front().where.str(), f.path, msg));
  }
  throw InputError(fmt::format("{}: key 'experiment': {}", spec.experiment_where.str(), msg));
}

}  // namespace

Experiment load_job_experiment(const SweepSpec& spec, const Job& job, PluginRegistry& registry) {
  try {
    return load_experiment_file(spec.experiment, registry, job_options(job));
  } catch (const InputError& e) {
    rethrow_located(spec, &job, e);
  }
}

BaseExperiment resolve_jobs(const SweepSpec& spec, std::vector<Job>& jobs, PluginRegistry& registry,
                            std::optional<int> only) {
  BaseExperiment base;
  try {
    const Experiment exp = load_experiment_file(spec.experiment, registry);
    base.name = exp.name;
    base.hash = content_hash(exp.resolved_yaml());
  } catch (const InputError& e) {
    rethrow_located(spec, nullptr, e);
  }
  for (Job& job : jobs) {
    if (only && job.index != *only) continue;
    const Experiment exp = load_job_experiment(spec, job, registry);
    job.resolved_seed = exp.seed;
    job.resolved_hash = content_hash(exp.resolved_yaml());
  }
  return base;
}

std::string jobs_tsv(const std::vector<Job>& jobs) {
  std::string out = "index\tfolder\tseed\toverrides\n";
  for (const Job& job : jobs) {
    out += fmt::format("{}\t{}\t{}", job.index, job.folder, job.resolved_seed);
    for (const Override& o : job.overrides) out += "\t" + o.path + "=" + o.value;
    out += "\n";
  }
  return out;
}

}  // namespace somasim::sweep
