#include "commands.hpp"
#include "mpi_session.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>  // mkdtemp (POSIX)
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <spdlog/sinks/null_sink.h>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"
#include "somasim/experiment.hpp"
#include "somasim/interrupt.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/pps/ini_export.hpp"
#include "somasim/pps/learned_file.hpp"
#include "somasim/runner.hpp"
#include "somasim/simulation.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::app {
namespace fs = std::filesystem;

namespace {

std::vector<Override> parse_sets(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set '" + s +
                       "': expected path=value, e.g. nodes.pps.params.threshold=0.2");
    out.push_back({s.substr(0, eq), s.substr(eq + 1)});
  }
  return out;
}

// Holds the run folder for this process: an exclusive lock on the folder itself (flock, released
// when the process ends, however it ends). A second run into the same folder is refused while
// this one lives.
void lock_run_folder(const fs::path& dir) {
  static int held = -1;  // kept open for the process's lifetime
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw InputError("cannot open run folder '" + dir.string() + "'");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK)
      throw InputError("run folder '" + dir.string() +
                       "' is in use by another somasim run; wait for it or choose another --out");
    // A file system without flock (some NFS mounts): run without the lock, and say so.
    fmt::print(stderr,
               "warning: cannot lock run folder '{}' ({}); a second run into it would "
               "not be refused\n",
               dir.string(), std::strerror(error));
    return;
  }
  if (held >= 0) ::close(held);
  held = fd;
}

// Creates the run folder, or empties an existing one with `overwrite`; an existing non-empty
// folder is refused otherwise (its files would mix with this run's), and so is one another run
// holds. --overwrite empties only a real folder, not one reached through a symbolic link (the
// link's target would be emptied). InputError when it cannot be made a fresh, writable folder.
void prepare_run_folder(const fs::path& dir, bool overwrite) {
  std::error_code ec;
  const auto status = fs::status(dir, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw InputError("--out '" + dir.string() + "' exists and is not a folder");
  // (The link itself: "out/" or "out/." would be resolved through it by lstat.)
  fs::path named = dir;
  while (!named.empty() && (named.filename().empty() || named.filename() == "."))
    named = named.parent_path();
  if (fs::is_directory(status) && !fs::is_empty(dir, ec) && overwrite &&
      fs::is_symlink(fs::symlink_status(named, ec)))
    throw InputError("--out '" + dir.string() +
                     "' is a symbolic link; --overwrite empties only a real folder (give the "
                     "folder's own path)");
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cannot create run folder '" + dir.string() + "': " + ec.message());
  lock_run_folder(dir);
  if (!fs::is_empty(dir, ec)) {
    if (!overwrite)
      throw InputError("run folder '" + dir.string() +
                       "' already holds a run; choose another --out or add --overwrite "
                       "(which empties it first)");
    std::vector<fs::path> entries;
    for (const auto& entry : fs::directory_iterator(dir, ec)) entries.push_back(entry.path());
    for (const fs::path& entry : entries) {
      std::error_code removed;
      fs::remove_all(entry, removed);
      if (removed && !ec) ec = removed;  // the first failure is the one reported
    }
    if (ec) throw InputError("cannot empty run folder '" + dir.string() + "': " + ec.message());
  }
  const fs::path probe = dir / ".somasim-write-test";
  if (std::FILE* f = std::fopen(probe.c_str(), "w")) {
    std::fclose(f);
    fs::remove(probe, ec);
  } else {
    throw InputError("cannot write into run folder '" + dir.string() + "'");
  }
}

// What validate adds to the file checks: every node's configure() (robots, learned maps,
// meshes, scene files and output names are read and checked), into a scratch run folder that
// is removed afterwards; nothing is stepped.
void configure_without_running(const Experiment& exp) {
  std::string scratch = (fs::temp_directory_path() / "somasim-validate-XXXXXX").string();
  if (!::mkdtemp(scratch.data())) throw RunError("cannot create a scratch folder for validate");
  struct RemoveOnExit {
    fs::path dir;
    ~RemoveOnExit() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } remove{scratch};
  auto logger =
      std::make_shared<spdlog::logger>("validate", std::make_shared<spdlog::sinks::null_sink_mt>());
  Simulation sim(exp, scratch, logger);
  sim.configure();
}

int bad_input(const std::exception& e) {
  fmt::print(stderr, "error: {}\n", escape_control_bytes(e.what()));
  return kExitBadInput;
}

}  // namespace

// One rank's run (the only one without MPI: mpi_session.hpp).
static int run_rank(const CommonOptions& common, const RunArgs& args, MpiSession& mpi) {
  PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
  Experiment exp;
  try {
    LoadOptions options;
    options.overrides = parse_sets(args.sets);
    if (!args.seed.empty()) {
      options.seed = parse_seed(args.seed);
      if (!options.seed)
        throw InputError(std::string("--seed: expected ") + kSeedExpectation + ", got '" +
                         args.seed + "'");
    }
    exp = load_experiment_file(args.file, registry, options);
  } catch (const InputError& e) {
    return bad_input(e);
  }
  RunOptions run;
  run.out_dir = mpi.run_folder(args.out.empty() ? fs::path("runs") / exp.name : fs::path(args.out));
  run.quiet = args.quiet || !mpi.is_root();
  run.progress_every_s = args.progress_every_s;
  try {
    prepare_run_folder(run.out_dir, args.overwrite);
  } catch (const InputError& e) {
    return bad_input(e);
  }
  install_interrupt_handler();
  const RunReport report = run_experiment(exp, run);
  const fs::path out = fs::absolute(run.out_dir).lexically_normal();
  switch (report.status) {
    case RunStatus::Completed:
      if (mpi.is_root()) fmt::print("results: {}\n", out.string());
      return kExitOk;
    case RunStatus::BadInput:
      fmt::print(stderr, "error: {}\n(partial results: {})\n", escape_control_bytes(report.error),
                 out.string());
      return kExitBadInput;
    case RunStatus::Failed:
      fmt::print(stderr, "run failed: {}\n(outputs flushed to {})\n",
                 escape_control_bytes(report.error), out.string());
      return kExitRunFailed;
    case RunStatus::Interrupted:
      fmt::print(stderr, "interrupted: outputs flushed to {}\n", out.string());
      return kExitInterrupted;
  }
  return kExitRunFailed;
}

int cmd_run(const CommonOptions& common, const RunArgs& args) {
  MpiSession mpi;  // MPI only under mpirun
  try {
    return mpi.end(run_rank(common, args, mpi));
  } catch (const std::exception& e) {
    if (!mpi.active()) throw;  // main's handler reports it
    fmt::print(stderr, "error: {}\n", escape_control_bytes(e.what()));
    return mpi.end(dynamic_cast<const InputError*>(&e) ? kExitBadInput : kExitRunFailed);
  }
}

int cmd_validate(const CommonOptions& common, const std::string& file,
                 const std::vector<std::string>& sets) {
  PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
  try {
    LoadOptions options;
    options.overrides = parse_sets(sets);
    const Experiment exp = load_experiment_file(file, registry, options);
    configure_without_running(exp);
    fmt::print("{}: ok ({} nodes, {} s at {} Hz)\n", file, exp.nodes.size(), exp.duration_s,
               exp.base_rate_hz);
    // What was loaded to check it (each library's constructors ran).
    for (const auto& lib : registry.opened_libraries())
      fmt::print("  plugin library loaded: {}\n", lib.string());
    return kExitOk;
  } catch (const InputError& e) {
    return bad_input(e);
  }
}

int cmd_plugins(const CommonOptions& common) {
  PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
  const auto listing = registry.list();
  for (const auto& l : listing) fmt::print("{:<22} {}\n", l.plugin.name, l.plugin.summary);
  if (listing.empty()) fmt::print(stderr, "no plugins found; {}\n", registry.search_report());
  // What was dlopen'ed to make this list (its constructors ran), and what was read from an index.
  bool header = false;
  for (const auto& c : registry.candidates()) {
    if (c.rejected()) continue;
    if (!header) fmt::print("\nlibraries:\n");
    header = true;
    fmt::print(
        "  {}: {}\n", c.path.string(),
        c.opened ? "loaded (dlopen'ed): " + c.index_note : std::string("index read, not loaded"));
  }
  for (const auto& c : registry.candidates())
    if (c.rejected()) fmt::print(stderr, "rejected {}: {}\n", c.path.string(), c.rejection);
  return kExitOk;
}

int cmd_index_plugins(const std::vector<std::string>& libraries) {
  for (const auto& lib : libraries) {
    try {
      index_plugin_library(lib);
    } catch (const InputError& e) {
      return bad_input(e);
    }
  }
  return kExitOk;
}

int cmd_describe(const CommonOptions& common, const std::string& name) {
  PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
  const PluginSpec* spec = registry.find(name);
  if (!spec) {
    fmt::print(stderr, "error: unknown plugin '{}'{}; {}\n", name,
               did_you_mean(name, registry.names()), registry.search_report());
    return kExitBadInput;
  }
  fmt::print("{}\n  {}\n  library: {}\n\nparameters:\n", spec->name(), spec->doc(),
             spec->library_path);
  for (const auto& p : spec->params()) {
    std::string type = param_type_name(p.type);
    if (p.type == ParamType::DoubleList && p.list_size)
      type = fmt::format("a list of {} numbers", *p.list_size);
    if (p.type == ParamType::StringList && p.list_size)
      type = fmt::format("a list of {} words", *p.list_size);
    if (p.map_as_text) type += " ('name: value, ...') or a map";
    std::string line = fmt::format("  {:<24} {}", p.name, type);
    if (!p.unit.empty()) line += " [" + p.unit + "]";
    line += p.default_value ? ", default " + param_value_str(*p.default_value) : ", required";
    if (p.min || p.max)
      line += fmt::format(", range [{}, {}]", p.min ? fmt::format("{}", *p.min) : "-inf",
                          p.max ? fmt::format("{}", *p.max) : "inf");
    if (!p.choices.empty()) line += ", one of: " + join_names(p.choices);
    if (p.max_list_size) line += fmt::format(", at most {} elements", *p.max_list_size);
    fmt::print("{}\n      {}\n", line, p.doc);
  }
  for (auto dir : {PortDirection::Input, PortDirection::Output}) {
    fmt::print("\n{}:\n", dir == PortDirection::Input ? "inputs" : "outputs");
    bool any = false;
    for (const auto& p : spec->ports())
      if (p.direction == dir) {
        any = true;
        fmt::print("  {:<24} {}{}{}\n      {}\n", p.name, p.type->name,
                   p.type->header.empty() ? "" : " (" + p.type->header + ")",
                   p.optional ? " (optional)" : "", p.doc);
      }
    if (!any) fmt::print("  (none)\n");
  }
  return kExitOk;
}

int cmd_pps_convert(const std::string& input, const std::string& output) {
  try {
    const pps::LearnedFile file = pps::load_learned_file(input, {}, pps::ParzenSpec::code());
    pps::save_learned_file(file.parts, output);
    std::string parts;
    for (const auto& p : file.parts)
      parts +=
          fmt::format("{}{} ({} taxels)", parts.empty() ? "" : ", ", p.body_part, p.taxels.size());
    fmt::print("{} -> {}: {}\n", input, output, parts);
    if (!file.has_geometry && !pps::is_ini_learned_file(output))
      fmt::print(stderr,
                 "note: {} holds no taxel geometry; {} has positions 0 and normals +z. Load the "
                 ".ini itself into pps_learner to take the geometry from the skin.\n",
                 input, output);
    return kExitOk;
  } catch (const InputError& e) {
    return bad_input(e);
  }
}

int cmd_graph(const CommonOptions& common, const std::string& file) {
  PluginRegistry registry(PluginRegistry::default_search_path(common.plugin_path));
  try {
    fmt::print("{}", load_experiment_file(file, registry).graphviz());
    return kExitOk;
  } catch (const InputError& e) {
    return bad_input(e);
  }
}

}  // namespace somasim::app
