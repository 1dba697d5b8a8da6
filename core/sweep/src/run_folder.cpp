// The sweep's files on disk: sweep.json and jobs.tsv in the output root, and what a run folder
// says about its run.
#include "somasim/sweep/run_folder.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/sweep/hash.hpp"

#ifndef SOMASIM_GIT_REVISION
#define SOMASIM_GIT_REVISION "unknown"
#endif

namespace somasim::sweep {
namespace fs = std::filesystem;

namespace {

std::optional<nlohmann::json> read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // half-written: the run is redone
  }
}

std::string string_field(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

const char* git_revision() {
  return SOMASIM_GIT_REVISION;
}

RunState run_state(const fs::path& run_dir, const Job& job) {
  const auto metrics = read_json(run_dir / "metrics.json");
  const auto resolved = file_hash(run_dir / "experiment.resolved.yaml");
  const bool same_experiment = resolved && *resolved == job.resolved_hash;
  if (metrics && same_experiment && string_field(*metrics, "status") == "completed")
    return RunState::kCompleted;
  if (const auto manifest = read_json(run_dir / "manifest.json")) {
    const std::string status = string_field(*manifest, "exit_status");
    if (string_field(*manifest, "resolved_hash") == job.resolved_hash &&
        (status == "failed" || status == "bad_input" || status == "crashed"))
      return RunState::kFailed;
  }
  return RunState::kRedo;
}

nlohmann::ordered_json sweep_manifest(const SweepSpec& spec, const BaseExperiment& base,
                                      const std::vector<Job>& jobs) {
  nlohmann::ordered_json m;
  m["sweep"] = spec.name;
  m["sweep_file"] = fs::absolute(spec.file).lexically_normal().string();
  m["experiment"] = base.name;
  m["experiment_file"] = spec.experiment.string();
  m["base_hash"] = base.hash;
  m["mode"] = spec.mode == SweepMode::kZip ? "zip" : "grid";
  m["axes"] = nlohmann::ordered_json::array();
  for (const Axis& a : spec.axes) {
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    for (const AxisValue& v : a.values) values.push_back(v.text);
    m["axes"].push_back({{"path", a.path}, {"values", values}});
  }
  if (!spec.summary_metric.empty())
    m["summary"] = {{"metric", spec.summary_metric}, {"against", spec.summary_against}};
  m["jobs"] = nlohmann::ordered_json::array();
  for (const Job& j : jobs) {
    nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
    for (const Override& o : j.overrides) overrides[o.path] = o.value;
    m["jobs"].push_back({{"index", j.index},
                         {"folder", j.folder},
                         {"seed", j.resolved_seed},
                         {"values", j.axis_values},
                         {"overrides", overrides},
                         {"resolved_hash", j.resolved_hash}});
  }
  return m;
}

void check_no_links_below(const fs::path& root, const std::string& relative) {
  fs::path at = root;
  for (const auto& part : fs::path(relative)) {
    at /= part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec)))
      throw InputError("'" + at.string() +
                       "' is a symbolic link inside the sweep's output folder; the sweep empties "
                       "run folders before each run and does not delete through links it did not "
                       "make (nothing was deleted; remove the link)");
  }
}

void write_file_atomically(const fs::path& file, const std::string& text) {
  const fs::path tmp = file.string() + fmt::format(".tmp.{}", ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError("cannot write '" + tmp.string() + "'");
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) throw InputError("cannot write '" + file.string() + "': " + ec.message());
}

nlohmann::json read_sweep_manifest(const fs::path& root) {
  const fs::path file = root / "sweep.json";
  std::error_code ec;
  if (!fs::exists(file, ec))
    throw InputError("'" + root.string() +
                     "' is not a sweep's output folder (it has no sweep.json); run `somasim "
                     "sweep expand` or `sweep run` into it first");
  const auto m = read_json(file);
  if (!m || !m->is_object() || !m->contains("jobs") || !(*m)["jobs"].is_array() ||
      !m->contains("axes") || !(*m)["axes"].is_array())
    throw InputError("'" + file.string() +
                     "' is not a sweep manifest (damaged or written by "
                     "something else)");
  return *m;
}

void prepare_output_root(const fs::path& root, const SweepSpec& spec, const BaseExperiment& base,
                         const std::vector<Job>& jobs, bool rewrite) {
  std::error_code ec;
  const auto status = fs::status(root, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw InputError("output folder '" + root.string() + "' exists and is not a folder");
  bool have_manifest = false;
  if (fs::is_directory(status) && !fs::is_empty(root, ec)) {
    if (!fs::exists(root / "sweep.json", ec))
      throw InputError("output folder '" + root.string() +
                       "' holds files but no sweep.json: it is not a sweep's output folder; "
                       "choose another --out or empty it");
    const nlohmann::json old = read_sweep_manifest(root);
    const std::string old_name = string_field(old, "experiment");
    const std::string old_hash = string_field(old, "base_hash");
    if (old_name != base.name || old_hash != base.hash)
      throw InputError(fmt::format(
          "output folder '{}' holds runs of another base experiment: its sweep.json names '{}' "
          "({}), this sweep runs '{}' ({}, from {}); choose another --out or remove that folder",
          root.string(), old_name, old_hash, base.name, base.hash, spec.experiment.string()));
    have_manifest = true;
  }
  fs::create_directories(root / "logs", ec);
  if (ec) throw InputError("cannot create output folder '" + root.string() + "': " + ec.message());
  if (rewrite || !have_manifest) {
    write_file_atomically(root / "sweep.json", sweep_manifest(spec, base, jobs).dump(2) + "\n");
    write_file_atomically(root / "jobs.tsv", jobs_tsv(jobs));
  }
}

}  // namespace somasim::sweep
