// somasim_param_fuzz: a schema-driven parameter fuzzer. For every plugin on the search path it
// reads the declared schema (each parameter's type, range, choices and list bounds) and
// generates values at and beyond every bound — 0, ±1, the range's ends and one step past them,
// the member type's limits and one past, 2^32, 2^63, NaN, ±inf, 1e±300, wrong types, empty and
// huge lists, lists one longer than allowed, file names that collide with the run's own files or
// climb out of the run folder, special files (/dev/zero, a FIFO, a folder) — one parameter at a
// time and then random combinations. Each case builds the plugin alone in the test harness
// (every input wired to the harness; joint states filled with zeros for the robot), validates
// and configures it, and runs a few ticks, in a child process with limits. Invariants:
//   - the child exits with 0 (accepted and ran), 2 (refused: InputError) or 3 (failed at run
//     time: RunError); no signal, no other exception;
//   - no hang (a time limit per case) and memory under a cap (peak RSS);
//   - nothing written outside the run folder (the child's working and temporary folders are
//     checked afterwards);
//   - a refusal (2) names the node and a key ("node 'n', key '...'").
// Usage: somasim_param_fuzz [--seconds N] [--plugin NAME] [--seed S] [--case-seconds T]
//                           [--robot FILE] [--verbose]
// Prints the cases per plugin and outcome, every violation with its case, and exits 1 if any.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "somasim/error.hpp"
#include "somasim/param.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/plugin_spec.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_loader.hpp"
#include "somasim/testing/harness.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

constexpr long kMaxRssKiB = 3L * 1024 * 1024;  // the memory cap a case may reach [KiB]
constexpr int kTicks = 5;                      // ticks run after a case is accepted

struct Options {
  double seconds = 60;
  double case_seconds = 60;
  std::string plugin;
  std::uint64_t seed = 1;
  std::string robot = SOMASIM_SOURCE_DIR "/assets/robots/icub_v1.yaml";
  /// With a folder of experiments: each plugin is fuzzed in the first of them that uses it (the
  /// real graph around it, `somasim run --set ...` for a short time) instead of alone.
  std::string configs;
  double run_seconds = 0.3;  ///< simulated time of an in-config case [s]
  bool verbose = false;
};

// Where a plugin is fuzzed in-config: an experiment file and the node that uses it.
struct Host {
  fs::path config;
  std::string node;
};

// One generated case: parameter name -> YAML text of its value.
using Case = std::vector<std::pair<std::string, std::string>>;

std::string repeat_list(const std::string& element, std::size_t n) {
  std::string out = "[";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + element;
  return out + "]";
}

std::string number(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  return fmt::format("{:.17g}", x);
}

// Scalars that are wrong for every type but their own, and special values.
const std::vector<std::string> kOddScalars = {"",       "abc", "[1]",  "{a: 1}",  "~",
                                              "'0x10'", "1e",  "true", "\"\\n\"", "\"a\\x01b\""};

std::vector<std::string> numbers_for(const somasim::ParamSpec& p) {
  std::vector<double> v = {0.0,
                           -0.0,
                           1.0,
                           -1.0,
                           0.5,
                           1e-300,
                           -1e-300,
                           1e300,
                           -1e300,
                           5e-324,
                           4294967296.0,
                           4294967297.0,
                           9223372036854775808.0,
                           std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
  for (const auto& b : {p.min, p.max})
    if (b) {
      const double step = std::max(1e-9, std::abs(*b) * 1e-9);
      v.insert(v.end(), {*b, *b - step, *b + step, *b - 1, *b + 1, std::nextafter(*b, -INFINITY),
                         std::nextafter(*b, INFINITY)});
    }
  std::vector<std::string> out;
  for (double x : v) out.push_back(number(x));
  return out;
}

std::vector<std::string> integers_for(const somasim::ParamSpec& p) {
  std::vector<std::string> out = {"0",
                                  "1",
                                  "-1",
                                  "2",
                                  "7",
                                  "4294967296",
                                  "4294967297",
                                  "9223372036854775807",
                                  "9223372036854775808",
                                  "-9223372036854775809",
                                  "1.5",
                                  "1e3",
                                  "100000000",
                                  "2147483648",
                                  "-2147483649"};
  for (const auto& b : {p.min, p.max})
    if (b && std::abs(*b) < 9e18) {
      const auto i = static_cast<long long>(std::llround(*b));
      for (long long d : {-1LL, 0LL, 1LL}) out.push_back(std::to_string(i + d));
    }
  for (const auto& b : {p.int_min, p.int_max})
    if (b) {
      out.push_back(std::to_string(*b));
      if (*b > std::numeric_limits<std::int64_t>::min()) out.push_back(std::to_string(*b - 1));
      if (*b < std::numeric_limits<std::int64_t>::max()) out.push_back(std::to_string(*b + 1));
    }
  return out;
}

std::vector<std::string> strings_for(const somasim::ParamSpec& p, const fs::path& fifo) {
  std::vector<std::string> out = {"''",
                                  "x",
                                  "metrics.json",
                                  "log.txt",
                                  "experiment.resolved.yaml",
                                  "./metrics.json",
                                  "figures/x.png",
                                  "frames/a",
                                  "../escaped.csv",
                                  "../../etc/passwd",
                                  "/tmp/somasim_fuzz_abs.csv",
                                  "/dev/zero",
                                  "/dev/urandom",
                                  "/",
                                  "'" + fifo.string() + "'",
                                  "sub/../log.txt",
                                  "'a: 1, b: 2'",
                                  "'r_elbow: 1e300'",
                                  "'r_elbow: .nan'",
                                  "left_eye",
                                  "nonexistent.json",
                                  "\"" + std::string(5000, 'a') + "\""};
  for (const std::string& c : p.choices) {
    out.push_back(c);
    out.push_back(c + "x");
    out.push_back(c.substr(0, c.size() / 2));
  }
  return out;
}

// Every value the fuzzer tries for one parameter.
std::vector<std::string> values_for(const somasim::ParamSpec& p, const fs::path& fifo) {
  using somasim::ParamType;
  std::vector<std::string> out = kOddScalars;
  std::vector<std::string> elements;
  switch (p.type) {
    case ParamType::Bool:
      out.insert(out.end(), {"false", "yes", "2", "0"});
      break;
    case ParamType::Int:
      for (const auto& s : integers_for(p)) out.push_back(s);
      break;
    case ParamType::Double:
      for (const auto& s : numbers_for(p)) out.push_back(s);
      break;
    case ParamType::String:
      for (const auto& s : strings_for(p, fifo)) out.push_back(s);
      break;
    case ParamType::DoubleList:
      elements = numbers_for(p);
      break;
    case ParamType::StringList:
      elements = strings_for(p, fifo);
      break;
  }
  if (!elements.empty()) {
    const std::string good = elements.front();
    out.push_back("[]");
    for (const auto& e : elements) out.push_back("[" + e + "]");
    for (std::size_t n : {std::size_t{2}, std::size_t{3}, std::size_t{6}, std::size_t{7}})
      out.push_back(repeat_list(good, n));
    if (p.list_size) {
      out.push_back(repeat_list(good, *p.list_size + 1));
      if (*p.list_size > 0) out.push_back(repeat_list(good, *p.list_size - 1));
    }
    if (p.max_list_size) out.push_back(repeat_list(good, *p.max_list_size + 1));
    out.push_back(repeat_list(good, 100000));
    out.push_back("[[1, 2], [3]]");
  }
  return out;
}

std::string yaml_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

// The experiment of one case: the plugin alone, every input wired to the harness.
std::string graph(const Options& o, const somasim::PluginSpec& spec, const Case& c) {
  std::string params;
  for (const auto& [name, value] : c)
    params += fmt::format("{}{}: {}", params.empty() ? "" : ", ", name, value);
  std::string inputs;
  for (const auto& port : spec.ports())
    if (port.direction == somasim::PortDirection::Input)
      inputs += fmt::format("{}{}: harness.{}", inputs.empty() ? "" : ", ", port.name, port.name);
  return fmt::format(
      "experiment: fuzz\nseed: 7\nbase_rate_hz: 100\nduration_s: 10\nrobots: {{icub: {}}}\n"
      "nodes:\n  n:\n    plugin: {}\n    params: {{{}}}\n    inputs: {{{}}}\n",
      yaml_quoted(o.robot), spec.name(), params, inputs);
}

enum Outcome { kAccepted = 0, kRefused = 2, kFailed = 3 };

// The child's work: builds and runs the case; returns 0/2/3, or 10 for a refusal that names no
// node or key, 11 for another exception, 12 for an allocation that failed (with the text on
// stderr). The harness is gone (its run folder removed) when this returns.
int run_case(const Options& o, const somasim::PluginSpec& spec, const std::string& text) {
  try {
    somasim::testing::Harness h(text);
    const auto model = somasim::robot::load_robot_model_shared(o.robot);
    for (const auto& port : spec.ports())
      if (port.direction == somasim::PortDirection::Input && port.type &&
          port.type->name == std::string(somasim::PortTraits<somasim::JointState>::name)) {
        auto& q = h.input<somasim::JointState>(port.name);
        q.position = Eigen::VectorXd::Zero(model->num_dofs());
        q.velocity = Eigen::VectorXd::Zero(model->num_dofs());
      }
    h.step(kTicks);
    return h.finish().empty() ? kAccepted : kFailed;
  } catch (const somasim::InputError& e) {
    const std::string what = e.what();
    if (what.find("node 'n'") == std::string::npos || what.find("key '") == std::string::npos) {
      std::fprintf(stderr, "refusal without node and key: %s\n", what.c_str());
      return 10;
    }
    std::fprintf(stderr, "refused: %s\n", what.c_str());
    return kRefused;
  } catch (const somasim::RunError& e) {
    std::fprintf(stderr, "failed: %s\n", e.what());
    return kFailed;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "out of memory (bad_alloc)\n");
    return 12;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unexpected exception: %s\n", e.what());
    return 11;
  }
}

// The path of the somasim program next to this one.
fs::path somasim_program() {
  std::error_code ec;
  return fs::read_symlink("/proc/self/exe", ec).parent_path() / "somasim";
}

// The child's work in-config: exec `somasim run` on the host experiment with the case's values.
[[noreturn]] void exec_in_config(const Options& o, const Host& host, const Case& c) {
  std::vector<std::string> args = {somasim_program().string(),
                                   "run",
                                   host.config.string(),
                                   "--out",
                                   "out",
                                   "--quiet",
                                   "--set",
                                   fmt::format("duration_s={}", o.run_seconds)};
  for (const auto& [name, value] : c) {
    args.push_back("--set");
    args.push_back(fmt::format("nodes.{}.params.{}={}", host.node, name, value));
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  std::_Exit(21);
}

struct Tally {
  int cases = 0, accepted = 0, refused = 0, failed = 0, violations = 0;
};

bool empty_dir(const fs::path& d) {
  std::error_code ec;
  return fs::is_empty(d, ec);
}

// Runs one case in a child; returns the violation ("" when the invariants hold).
std::string check_case(const Options& o, const somasim::PluginSpec& spec, const Case& c,
                       const fs::path& work, Tally& t, const Host* host) {
  const fs::path cwd = work / "cwd", tmp = work / "tmp";
  std::error_code ec;
  fs::remove_all(cwd, ec);
  fs::remove_all(tmp, ec);
  fs::create_directories(cwd);
  fs::create_directories(tmp);
  const std::string text = graph(o, spec, c);
  const fs::path err_file = work / "stderr";
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(cwd.c_str()) != 0) std::_Exit(20);
    setenv("TMPDIR", tmp.c_str(), 1);
    const int fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 2);
      dup2(fd, 1);
    }
    const rlimit cpu{static_cast<rlim_t>(o.case_seconds), static_cast<rlim_t>(o.case_seconds + 5)};
    setrlimit(RLIMIT_CPU, &cpu);
    alarm(static_cast<unsigned>(o.case_seconds));
    if (host) exec_in_config(o, *host, c);
    const int code = run_case(o, spec, text);
    std::fflush(nullptr);
    std::_Exit(code);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  ++t.cases;
  std::string violation;
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    violation = sig == SIGALRM || sig == SIGXCPU
                    ? fmt::format("hang: no result in {} s", o.case_seconds)
                    : fmt::format("killed by signal {} ({})", sig, strsignal(sig));
  } else {
    const int code = WEXITSTATUS(status);
    if (code == kAccepted)
      ++t.accepted;
    else if (code == kRefused)
      ++t.refused;
    else if (code == kFailed)
      ++t.failed;
    else
      violation = fmt::format("exit {}", code);
  }
  if (violation.empty() && usage.ru_maxrss > kMaxRssKiB)
    violation = fmt::format("peak memory {} MiB over the cap", usage.ru_maxrss / 1024);
  if (violation.empty()) {
    for (const auto& e : fs::directory_iterator(cwd, ec))
      if (!host || e.path().filename() != "out")
        violation = "wrote into the working folder: " + e.path().filename().string();
  }
  // In-config refusals: the message names the node and a key.
  if (violation.empty() && host && WIFEXITED(status) && WEXITSTATUS(status) == kRefused) {
    std::ifstream in(err_file);
    const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (err.find("node '") == std::string::npos || err.find("key '") == std::string::npos)
      violation = "refusal without node and key";
  }
  if (violation.empty() && !empty_dir(tmp)) violation = "left files in the temporary folder";
  if (violation.empty() && fs::exists("/tmp/somasim_fuzz_abs.csv")) {
    fs::remove("/tmp/somasim_fuzz_abs.csv", ec);
    violation = "wrote to an absolute path outside the run folder";
  }
  if (!violation.empty()) {
    ++t.violations;
    std::ifstream in(err_file);
    std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (err.size() > 2000) err = err.substr(err.size() - 2000);
    std::string shown;
    for (const auto& [k, v] : c) shown += fmt::format(" {}={}", k, v.substr(0, 120));
    fmt::print("VIOLATION {}:{} -> {}\n  {}\n", spec.name(), shown, violation, err);
  }
  return violation;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        fmt::print(stderr, "{} needs a value\n", a);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--seconds")
      o.seconds = std::stod(next());
    else if (a == "--case-seconds")
      o.case_seconds = std::stod(next());
    else if (a == "--plugin")
      o.plugin = next();
    else if (a == "--seed")
      o.seed = std::stoull(next());
    else if (a == "--robot")
      o.robot = next();
    else if (a == "--verbose")
      o.verbose = true;
    else if (a == "--configs")
      o.configs = next();
    else if (a == "--run-seconds")
      o.run_seconds = std::stod(next());
    else {
      fmt::print(stderr,
                 "usage: somasim_param_fuzz [--seconds N] [--plugin NAME] [--seed S] "
                 "[--case-seconds T] [--robot FILE] [--configs DIR [--run-seconds S]] "
                 "[--verbose]\n");
      return 2;
    }
  }
  setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  char work_template[] = "/tmp/somasim-param-fuzz-XXXXXX";
  const fs::path work = mkdtemp(work_template);
  const fs::path fifo = work / "fifo";
  mkfifo(fifo.c_str(), 0600);

  somasim::PluginRegistry registry(somasim::PluginRegistry::default_search_path({}));
  std::vector<const somasim::PluginSpec*> specs;
  for (const auto& l : registry.list())
    if (o.plugin.empty() || l.plugin.name == o.plugin)
      if (const auto* s = registry.find(l.plugin.name)) specs.push_back(s);
  if (specs.empty()) {
    fmt::print(stderr, "no plugin to fuzz\n");
    return 2;
  }
  std::map<std::string, Host> hosts;
  if (!o.configs.empty()) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(o.configs))
      if (e.path().extension() == ".yaml") files.push_back(e.path());
    std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
      return fs::file_size(a) < fs::file_size(b);  // the smallest experiment that uses it
    });
    for (const auto& f : files) {
      const YAML::Node nodes = YAML::LoadFile(f.string())["nodes"];
      if (!nodes.IsMap()) continue;
      for (const auto& kv : nodes)
        if (kv.second.IsMap() && kv.second["plugin"])
          hosts.try_emplace(kv.second["plugin"].as<std::string>(),
                            Host{fs::absolute(f), kv.first.as<std::string>()});
    }
    std::erase_if(specs, [&](const somasim::PluginSpec* s) { return !hosts.count(s->name()); });
  }
  // One parameter at a time, every plugin in turn; then random combinations until the time is up.
  std::map<std::string, std::vector<Case>> queue;
  for (const auto* s : specs)
    for (const auto& p : s->params())
      for (const auto& v : values_for(p, fifo)) queue[s->name()].push_back({{p.name, v}});
  std::map<std::string, Tally> tally;
  std::mt19937_64 rng(o.seed);
  const auto start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  bool more = true;
  std::size_t round = 0;
  while (more && elapsed() < o.seconds) {
    more = false;
    for (const auto* s : specs) {
      if (elapsed() >= o.seconds) break;
      auto& q = queue[s->name()];
      Case c;
      if (round < q.size()) {
        c = q[round];
      } else if (!s->params().empty()) {
        // A random combination of 2-4 parameters with generated values.
        std::uniform_int_distribution<std::size_t> pick(0, s->params().size() - 1);
        std::uniform_int_distribution<int> count(2, 4);
        for (int k = count(rng); k > 0; --k) {
          const auto& p = s->params()[pick(rng)];
          const auto values = values_for(p, fifo);
          std::uniform_int_distribution<std::size_t> v(0, values.size() - 1);
          bool dup = false;
          for (const auto& [name, value] : c) dup = dup || name == p.name;
          if (!dup) c.push_back({p.name, values[v(rng)]});
        }
      }
      more = true;
      const auto host = hosts.find(s->name());
      // (In-config cases go through the command line: a value longer than the system takes as
      // an argument is tried by the alone mode only.)
      if (host != hosts.end() &&
          std::any_of(c.begin(), c.end(), [](const auto& kv) { return kv.second.size() > 65536; }))
        continue;
      check_case(o, *s, c, work, tally[s->name()], host == hosts.end() ? nullptr : &host->second);
      if (o.verbose) {
        std::ifstream in(work / "stderr");
        std::string first;
        std::getline(in, first);
        std::string shown;
        for (const auto& [k, v] : c) shown += fmt::format(" {}={}", k, v.substr(0, 60));
        fmt::print("{}:{}: {}\n", s->name(), shown, first.substr(0, 300));
      }
    }
    ++round;
  }
  std::error_code ec;
  fs::remove_all(work, ec);
  int violations = 0, cases = 0;
  fmt::print("{:<22} {:>7} {:>9} {:>8} {:>7} {:>10}\n", "plugin", "cases", "accepted", "refused",
             "failed", "violations");
  for (const auto& [name, t] : tally) {
    fmt::print("{:<22} {:>7} {:>9} {:>8} {:>7} {:>10}\n", name, t.cases, t.accepted, t.refused,
               t.failed, t.violations);
    violations += t.violations;
    cases += t.cases;
  }
  fmt::print("{} cases in {:.0f} s over {} plugins, {} violations\n", cases, elapsed(),
             tally.size(), violations);
  return violations == 0 ? 0 : 1;
}
