#include "somasim/runner.hpp"

#include <unistd.h>

#include <chrono>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include "progress_report.hpp"
#include "somasim/atomic_file.hpp"
#include "somasim/error.hpp"
#include "somasim/interrupt.hpp"
#include "somasim/simulation.hpp"
#include "somasim/version.hpp"

namespace somasim {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const char* run_status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::BadInput:
      return "bad_input";
    case RunStatus::Failed:
      return "failed";
    case RunStatus::Interrupted:
      return "interrupted";
  }
  return "?";
}

namespace {

std::shared_ptr<spdlog::logger> make_logger(const fs::path& dir, bool quiet) {
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>((dir / "log.txt").string(), true);
  file->set_level(spdlog::level::debug);
  auto err = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  err->set_level(quiet ? spdlog::level::warn : spdlog::level::info);
  err->set_pattern("[%n] %^%l%$: %v");
  auto logger = std::make_shared<spdlog::logger>("somasim", spdlog::sinks_init_list{file, err});
  logger->set_level(spdlog::level::debug);
  logger->flush_on(spdlog::level::debug);  // every line reaches log.txt as it is logged
  return logger;
}

}  // namespace

void write_metrics_file(const fs::path& file, const nlohmann::ordered_json& metrics) {
  // Whole or not at all: a run killed meanwhile leaves the old metrics.json or the new one.
  // Invalid UTF-8 in a message or metric is replaced, not a reason to lose the file.
  write_file_atomically(
      file, metrics.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
}

namespace {

void write_metrics(const fs::path& file, const nlohmann::ordered_json& metrics) {
  write_metrics_file(file, metrics);
}

/// The plugin libraries the experiment's nodes come from, for the log.
std::string plugin_libraries(const Experiment& exp) {
  std::set<std::string> libs;
  for (const auto& n : exp.nodes)
    if (n.spec && !n.spec->library_path.empty()) libs.insert(n.spec->library_path);
  std::string out;
  for (const auto& l : libs) out += (out.empty() ? "" : ", ") + l;
  return out.empty() ? "none" : out;
}

RunReport run_in_folder(const Experiment& exp, const RunOptions& options);

}  // namespace

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

RunReport run_experiment(const Experiment& exp, const RunOptions& options) {
  try {
    return run_in_folder(exp, options);
  } catch (const std::exception& e) {
    // The run folder, the log or metrics.json itself failed: still report it, and leave a
    // metrics.json saying so if the folder can take one.
    RunReport report;
    report.status = RunStatus::Failed;
    report.error = e.what();
    report.stop_reason = report.error;
    report.metrics = {{"experiment", exp.name},
                      {"status", run_status_name(report.status)},
                      {"error", report.error},
                      {"stop_reason", report.stop_reason},
                      {"seed", exp.seed}};
    std::error_code ec;
    if (fs::is_directory(options.out_dir, ec)) {
      try {
        write_metrics(options.out_dir / "metrics.json", report.metrics);
      } catch (const std::exception&) {  // nothing more can be saved; the error is returned
      }
    }
    return report;
  }
}

namespace {

RunReport run_in_folder(const Experiment& exp, const RunOptions& options) {
  fs::create_directories(options.out_dir);
  // Until the run ends, metrics.json says it is running: a folder whose run was killed says so.
  write_metrics(options.out_dir / "metrics.json", {{"experiment", exp.name},
                                                   {"status", "running"},
                                                   {"seed", exp.seed},
                                                   {"pid", static_cast<long>(::getpid())},
                                                   {"host", host_name()}});
  write_file_atomically(options.out_dir / "experiment.resolved.yaml", exp.resolved_yaml());
  auto logger = make_logger(options.out_dir, options.quiet);
  logger->info("experiment '{}' from {}, seed {}, {} s at {} Hz, output in {}", exp.name,
               exp.file.string(), exp.seed, exp.duration_s, exp.base_rate_hz,
               options.out_dir.string());
  logger->info("plugin libraries: {}", plugin_libraries(exp));
  RunReport report;
  const auto wall_start = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - wall_start).count(); };
  Simulation sim(exp, options.out_dir, logger);
  bool started = false;
  try {
    sim.configure();
    sim.start();
    started = true;
    ProgressReport progress(options.progress && !options.quiet,
                            options.quiet ? 0.0 : options.progress_every_s, *logger);
    while (sim.step()) progress.update(sim, exp.duration_s, wall());
    if (sim.stop_reason() == "interrupted") report.status = RunStatus::Interrupted;
  } catch (const InputError& e) {
    report.status = RunStatus::BadInput;
    report.error = e.what();
  } catch (const std::exception& e) {
    report.status = RunStatus::Failed;
    report.error =
        fmt::format("node '{}' at t = {} s: {}", sim.current_node(), sim.time_s(), e.what());
  }
  report.stop_reason =
      report.status == RunStatus::Completed || report.status == RunStatus::Interrupted
          ? sim.stop_reason()
          : report.error;
  if (started || report.status != RunStatus::BadInput) {
    const std::string finish_error = sim.finish();
    if (!finish_error.empty() && report.status == RunStatus::Completed) {
      report.status = RunStatus::Failed;
      report.error = finish_error;
    }
  }
  const double wall_s = wall();
  auto& m = report.metrics;
  m["experiment"] = exp.name;
  m["status"] = run_status_name(report.status);
  m["error"] = report.error;
  m["stop_reason"] = report.stop_reason;
  m["seed"] = exp.seed;
  m["sim_time_s"] = sim.time_s();
  m["wall_time_s"] = wall_s;
  m["real_time_factor"] = wall_s > 0 ? sim.time_s() / wall_s : 0.0;
  m["versions"] = {{"somasim", kVersion},
                   {"plugin_interface", kPluginInterfaceVersion},
                   {"compiler", __VERSION__}};
  m["nodes"] = sim.node_metrics();
  write_metrics(options.out_dir / "metrics.json", m);
  if (report.status == RunStatus::Completed) {
    logger->info("completed ({}) in {:.2f} s wall time", report.stop_reason, wall_s);
  } else {
    // Into log.txt only: the caller reports the outcome to the user (the CLI in one line), so
    // echoing it on stderr here would say it twice.
    spdlog::logger file_only("somasim", logger->sinks().front());
    file_only.set_level(spdlog::level::debug);
    file_only.error("run {}: {}", run_status_name(report.status),
                    report.error.empty() ? report.stop_reason : report.error);
    file_only.flush();
  }
  logger->flush();
  return report;
}

}  // namespace

}  // namespace somasim
