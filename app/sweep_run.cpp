// `somasim sweep run` and `run-one`: each job is a child `somasim run` process, so a crash loses
// one run only; the parent writes the run's manifest.json when the child has ended.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <ctime>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "somasim/error.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/sweep/child_process.hpp"
#include "somasim/sweep/hash.hpp"
#include "somasim/sweep/run_folder.hpp"
#include "somasim/version.hpp"
#include "somasim/yaml_text.hpp"
#include "sweep_commands.hpp"
#include "sweep_setup.hpp"

namespace somasim::app {
namespace fs = std::filesystem;
using sweep::Job;
using Clock = std::chrono::steady_clock;

namespace {

volatile std::sig_atomic_t g_stop_requests = 0;

extern "C" void on_stop_signal(int /*sig*/) {
  g_stop_requests = g_stop_requests + 1;
}

// SIGINT/SIGTERM/SIGHUP set a flag and interrupt waitpid() (no SA_RESTART).
void install_stop_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::optional<nlohmann::json> read_json(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// Runs jobs as child processes and records each one's manifest.
class JobRunner {
 public:
  JobRunner(const CommonOptions& common, SweepSetup& setup, bool own_process_groups)
      : common_(common), setup_(setup), own_groups_(own_process_groups) {
    exe_ = sweep::self_executable();
  }

  struct Running {
    const Job* job = nullptr;
    Clock::time_point start;
    std::string started_at;
  };

  // Empties the job's run folder and starts `somasim run` on it.
  pid_t launch(const Job& job) {
    const fs::path run_dir = setup_.root / job.folder;
    std::error_code ec;
    fs::remove_all(run_dir, ec);
    fs::create_directories(run_dir.parent_path(), ec);
    const fs::path log = log_path(job);
    fs::remove(log, ec);
    std::vector<std::string> argv = {exe_.string()};
    for (const auto& p : common_.plugin_path)
      argv.insert(argv.end(), {"--plugin-path", fs::absolute(p).string()});
    argv.insert(argv.end(), {"run", setup_.spec.experiment.string()});
    for (const auto& o : job.overrides) argv.insert(argv.end(), {"--set", o.path + "=" + o.value});
    argv.insert(argv.end(), {"--seed", std::to_string(job.resolved_seed), "--out",
                             fs::absolute(run_dir).string(), "--quiet"});
    const pid_t pid = sweep::start_child(argv, log, own_groups_);
    running_[pid] = {&job, Clock::now(), utc_now()};
    return pid;
  }

  struct Outcome {
    const Job* job = nullptr;
    std::string status;  ///< completed, interrupted, failed, bad_input, crashed
    std::string error;   ///< why it did not complete
    double wall_s = 0;
  };

  // Records how the child ended in the run's manifest.json.
  Outcome finish(pid_t pid, int wait_status) {
    const Running r = running_.at(pid);
    running_.erase(pid);
    const Job& job = *r.job;
    const double wall = std::chrono::duration<double>(Clock::now() - r.start).count();
    const sweep::ChildExit exit = sweep::decode_wait_status(wait_status);
    const fs::path run_dir = setup_.root / job.folder;
    const auto metrics = read_json(run_dir / "metrics.json");
    const std::string metrics_status =
        metrics && metrics->is_object() ? metrics->value("status", "") : "";
    // Stopped by a signal that asks to stop (ours or the terminal's, possibly before the child
    // installed its handler), or by its own interrupt handling: interrupted, redone next time.
    // Any other signal is a crash.
    const bool stop_signal =
        exit.signal == SIGINT || exit.signal == SIGTERM || exit.signal == SIGHUP;
    const bool interrupted =
        stop_signal || (exit.signal == 0 && exit.code != kExitOk &&
                        (exit.code == kExitInterrupted || metrics_status == "interrupted"));
    std::string status;
    if (interrupted)
      status = "interrupted";
    else if (exit.signal != 0)
      status = "crashed";
    else if (exit.code == kExitOk)
      status = "completed";
    else if (exit.code == kExitBadInput)
      status = "bad_input";
    else
      status = "failed";
    std::string error = metrics && metrics->is_object() ? metrics->value("error", "") : "";
    if (error.empty() && status != "completed") error = exit.str();
    nlohmann::ordered_json m;
    m["sweep"] = setup_.spec.name;
    m["index"] = job.index;
    m["experiment"] = setup_.base.name;
    m["experiment_file"] = setup_.spec.experiment.string();
    m["resolved_hash"] = job.resolved_hash;
    m["resolved_hash_algorithm"] = "FNV-1a 64-bit of experiment.resolved.yaml";
    m["somasim_version"] = kVersion;
    m["git_revision"] = sweep::git_revision();
    m["plugin_interface"] = kPluginInterfaceVersion;
    m["plugin_libraries"] = libraries(job);
    m["seed"] = job.resolved_seed;
    nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
    for (const auto& o : job.overrides) overrides[o.path] = o.value;
    m["overrides"] = overrides;
    m["host"] = host_name();
    m["started_at"] = r.started_at;
    m["wall_time_s"] = wall;
    m["exit_status"] = status;
    m["exit_code"] = exit.code;
    if (exit.signal != 0) m["signal"] = exit.signal;
    m["log"] = fs::absolute(log_path(job)).lexically_normal().string();
    std::error_code ec;
    fs::create_directories(run_dir, ec);
    std::ofstream(run_dir / "manifest.json") << m.dump(2) << "\n";
    return {&job, status, error, wall};
  }

  // Sends `sig` to every running child.
  void signal_all(int sig) const {
    for (const auto& [pid, r] : running_) ::kill(pid, sig);
  }
  std::size_t running() const { return running_.size(); }
  fs::path log_path(const Job& job) const {
    return setup_.root / "logs" / (fs::path(job.folder).filename().string() + ".log");
  }

 private:
  // The plugin libraries the job's nodes come from, with what identifies their build.
  nlohmann::ordered_json libraries(const Job& job) {
    std::set<std::string> paths;
    try {
      const Experiment exp = sweep::load_job_experiment(setup_.spec, job, setup_.registry);
      for (const auto& n : exp.nodes)
        if (n.spec && !n.spec->library_path.empty()) paths.insert(n.spec->library_path);
    } catch (const InputError&) {  // checked before the run: cannot happen; keep the manifest
    }
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const auto& p : paths) {
      if (!library_hashes_.count(p))
        library_hashes_[p] = sweep::file_hash(p).value_or("unreadable");
      out.push_back(
          {{"path", p}, {"interface", kPluginInterfaceVersion}, {"hash", library_hashes_[p]}});
    }
    return out;
  }

  const CommonOptions& common_;
  SweepSetup& setup_;
  bool own_groups_;
  fs::path exe_;
  std::map<pid_t, Running> running_;
  std::map<std::string, std::string> library_hashes_;
};

std::string previous_error(const fs::path& run_dir) {
  const auto manifest = read_json(run_dir / "manifest.json");
  const auto metrics = read_json(run_dir / "metrics.json");
  std::string e = metrics && metrics->is_object() ? metrics->value("error", "") : "";
  if (e.empty() && manifest && manifest->is_object())
    e = manifest->value("exit_status", "") + ", exit code " +
        std::to_string(manifest->value("exit_code", -1));
  return e;
}

}  // namespace

int cmd_sweep_run(const CommonOptions& common, const SweepArgs& args) {
  if (args.workers < 1)
    throw InputError(fmt::format("-j {}: expected at least 1 worker", args.workers));
  SweepSetup setup(common, args, std::nullopt, true);
  const std::size_t n = setup.jobs.size();
  std::vector<const Job*> pending;
  struct Failure {
    const Job* job;
    std::string what;
  };
  std::vector<Failure> failures;
  std::size_t skipped = 0, completed = 0, interrupted = 0;
  for (const Job& job : setup.jobs) {
    switch (sweep::run_state(setup.root / job.folder, job)) {
      case sweep::RunState::kCompleted:
        ++skipped;
        break;
      case sweep::RunState::kFailed:
        if (args.retry_failed) {
          pending.push_back(&job);
        } else {
          failures.push_back({&job, job.folder + ": " + previous_error(setup.root / job.folder) +
                                        " (failed before; not re-run without --retry-failed)"});
        }
        break;
      case sweep::RunState::kRedo:
        pending.push_back(&job);
        break;
    }
  }
  for (const Job* job : pending) sweep::check_no_links_below(setup.root, job->folder);
  fmt::print("sweep {}: {} runs in {} ({} already completed, {} to run, {} workers)\n",
             setup.spec.name, n, setup.root.string(), skipped, pending.size(), args.workers);
  std::fflush(stdout);
  install_stop_handler();
  JobRunner runner(common, setup, true);
  std::size_t next = 0, done = 0;
  int forwarded = 0;
  while ((next < pending.size() && g_stop_requests == 0) || runner.running() > 0) {
    while (g_stop_requests == 0 && next < pending.size() &&
           runner.running() < static_cast<std::size_t>(args.workers))
      runner.launch(*pending[next++]);
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno != EINTR) break;
      // Each stop request is passed on once: the first lets the runs flush, a second kills.
      while (forwarded < g_stop_requests) {
        runner.signal_all(SIGINT);
        ++forwarded;
      }
      continue;
    }
    const JobRunner::Outcome o = runner.finish(pid, status);
    ++done;
    if (o.status == "completed") {
      ++completed;
      fmt::print("[{}/{}] {} completed ({:.1f} s)\n", done, pending.size(), o.job->folder,
                 o.wall_s);
    } else if (o.status == "interrupted") {
      ++interrupted;
      fmt::print("[{}/{}] {} interrupted\n", done, pending.size(), o.job->folder);
    } else {
      const std::string what =
          fmt::format("{}: {} (log: {})", o.job->folder, o.error, runner.log_path(*o.job).string());
      fmt::print("[{}/{}] {} {}: {}\n", done, pending.size(), o.job->folder, o.status,
                 escape_control_bytes(o.error));
      failures.push_back({o.job, what});
    }
    std::fflush(stdout);
  }
  const std::size_t not_started = pending.size() - next;
  fmt::print("sweep {}: {} runs: {} completed ({} skipped as already completed), {} failed",
             setup.spec.name, n, completed + skipped, skipped, failures.size());
  if (interrupted + not_started > 0)
    fmt::print(", {} interrupted, {} not started", interrupted, not_started);
  fmt::print("\n");
  std::sort(failures.begin(), failures.end(),
            [](const Failure& a, const Failure& b) { return a.job->index < b.job->index; });
  for (const auto& f : failures) fmt::print(stderr, "failed: {}\n", escape_control_bytes(f.what));
  if (g_stop_requests > 0) {
    fmt::print(stderr,
               "interrupted: {} runs left ({} interrupted, {} not started); run the same "
               "command again to resume\n",
               interrupted + not_started, interrupted, not_started);
    return kExitInterrupted;
  }
  return failures.empty() ? kExitOk : kExitRunFailed;
}

int cmd_sweep_run_one(const CommonOptions& common, const SweepArgs& args) {
  SweepSetup setup(common, args, args.index, false);
  const Job& job = setup.jobs.at(static_cast<std::size_t>(args.index));
  const fs::path run_dir = setup.root / job.folder;
  switch (sweep::run_state(run_dir, job)) {
    case sweep::RunState::kCompleted:
      fmt::print("{}: already completed (skipped)\n", job.folder);
      return kExitOk;
    case sweep::RunState::kFailed:
      if (!args.retry_failed) {
        fmt::print(stderr, "failed: {}: {} (failed before; not re-run without --retry-failed)\n",
                   job.folder, escape_control_bytes(previous_error(run_dir)));
        return kExitRunFailed;
      }
      break;
    case sweep::RunState::kRedo:
      break;
  }
  sweep::check_no_links_below(setup.root, job.folder);
  install_stop_handler();  // the child gets the same signals (same process group) and flushes
  JobRunner runner(common, setup, false);
  const pid_t pid = runner.launch(job);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw RunError("waiting for the run failed");
  const JobRunner::Outcome o = runner.finish(pid, status);
  if (o.status == "completed") {
    fmt::print("{}: completed ({:.1f} s)\n", job.folder, o.wall_s);
    return kExitOk;
  }
  if (o.status == "interrupted") {
    fmt::print(stderr, "interrupted: {} (run it again to redo it)\n", job.folder);
    return kExitInterrupted;
  }
  fmt::print(stderr, "failed: {}: {} (log: {})\n", job.folder, escape_control_bytes(o.error),
             runner.log_path(job).string());
  return o.status == "bad_input" ? kExitBadInput : kExitRunFailed;
}

}  // namespace somasim::app
