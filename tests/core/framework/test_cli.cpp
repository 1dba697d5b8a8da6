// The `somasim` program: exit codes, messages, subcommands, --set/--seed, signals.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {
namespace fs = std::filesystem;

const std::string kExperiment = R"(experiment: cli_test
seed: 1
duration_s: 0.005
nodes:
  c: {plugin: counter, params: {start: 0}}
  noise: {plugin: counter, params: {start: 0, mode: noisy}}
  s: {plugin: adder, inputs: {a: c.value, b: {from: s.sum, delayed: true}}}
record: [c.value, noise.value]
)";

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    unsetenv("SOMASIM_PLUGIN_PATH");  // only --plugin-path and the build tree's plugins
    write_file(dir / "exp.yaml", kExperiment);
  }
  nlohmann::json metrics(const std::string& run) const {
    return nlohmann::json::parse(read_file(dir / run / "metrics.json"));
  }
  TempDir dir;
};

TEST_F(Cli, HelpWorksForEverySubcommand) {
  for (const auto& args : std::vector<std::vector<std::string>>{{"--help"},
                                                                {"run", "--help"},
                                                                {"validate", "--help"},
                                                                {"plugins", "--help"},
                                                                {"plugins", "describe", "--help"},
                                                                {"graph", "--help"}}) {
    const CliResult r = cli(args, dir, false);
    EXPECT_EQ(r.code, 0) << args.back();
    EXPECT_NE(r.out.find("Usage: "), std::string::npos) << r.out;
    EXPECT_EQ(r.err, "");
  }
  const CliResult top = cli({"--help"}, dir, false);
  EXPECT_NE(top.out.find("Exit codes: 0 success, 2 bad input"), std::string::npos);
  for (const char* sub : {"run", "validate", "plugins", "graph"})
    EXPECT_NE(top.out.find(sub), std::string::npos) << sub;
}

TEST_F(Cli, VersionNamesThePackageAndThePluginInterface) {
  const CliResult r = cli({"--version"}, dir, false);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("somasim 0.1.0 (plugin interface somasim-plugin-api/", 0), 0u) << r.out;
  EXPECT_EQ(r.err, "");
}

TEST_F(Cli, WithoutATerminalProgressIsLoggedWithTheNodesCount) {
  // stderr is a pipe here: progress comes as log lines, counted by the node that ends the run.
  write_file(dir / "long.yaml", R"(experiment: progress_test
duration_s: 100000
nodes:
  c: {plugin: counter, params: {start: 0, stop_after: 20000000}}
)");
  // (2e7 ticks take more than the shortest period, 0.1 s, on any machine.)
  const CliResult r = cli({"run", "long.yaml", "--out", "p", "--progress-every", "0.1"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const std::string log = read_file(dir / "p" / "log.txt");
  EXPECT_NE(log.find("progress: sim "), std::string::npos) << log;
  EXPECT_NE(log.find("/100000.0 s, counts "), std::string::npos) << log;
  EXPECT_NE(log.find("/20000000, "), std::string::npos) << log;
  EXPECT_NE(log.find(" ETA "), std::string::npos) << log;
  EXPECT_NE(r.err.find("progress: "), std::string::npos);
  // --quiet: none; 0: none.
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--quiet"}, {"--progress-every", "0"}}) {
    std::vector<std::string> args = {"run", "long.yaml", "--out", "q", "--overwrite"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult q = cli(args, dir);
    EXPECT_EQ(q.code, 0) << q.err;
    EXPECT_EQ(read_file(dir / "q" / "log.txt").find("progress: "), std::string::npos);
  }
  for (const char* bad : {"-1", "nan", "inf", "1e7", "x", "1e-300", "0.05"})
    EXPECT_EQ(cli({"run", "long.yaml", "--out", "b", "--progress-every", bad}, dir).code, 2) << bad;
}

TEST_F(Cli, PluginNewWritesAFolderAndRefusesBadNamesAndUsedFolders) {
  CliResult r = cli({"plugin", "new", "my_gain"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* f : {"CMakeLists.txt", "my_gain.cpp", "test_my_gain.cpp", "README.md"})
    EXPECT_TRUE(fs::is_regular_file(dir / "my_gain" / f)) << f;
  EXPECT_NE(read_file(dir / "my_gain" / "my_gain.cpp").find("class MyGain"), std::string::npos);
  r = cli({"plugin", "new", "my_gain"}, dir, false);  // the folder is used now
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("exists and is not an empty folder"), std::string::npos) << r.err;
  // Names: generated from a few characters each side of the rule.
  const std::string chars = "aZ0_-./ \n$;";
  for (char first : chars)
    for (char second : chars) {
      const std::string name = std::string(1, first) + second;
      const bool valid =
          first >= 'a' && first <= 'z' &&
          ((second >= 'a' && second <= 'z') || (second >= '0' && second <= '9') || second == '_');
      r = cli({"plugin", "new", name, "--dir", "n"}, dir, false);
      EXPECT_EQ(r.code, valid ? 0 : 2) << "'" << name << "': " << r.err;
      if (valid) fs::remove_all(dir / "n");
      EXPECT_FALSE(!valid && fs::exists(dir / "n")) << name;
    }
  EXPECT_EQ(cli({"plugin", "new", std::string(64, 'a'), "--dir", "n"}, dir, false).code, 2);
  for (const char* reserved : {"do", "if", "or", "int", "new", "linux", "a__b", "somasim"})
    EXPECT_EQ(cli({"plugin", "new", reserved, "--dir", "n"}, dir, false).code, 2) << reserved;
}

// A killed run (metrics.json still says running, its process gone): `recover` cuts every CSV
// back to its last whole row, follows no link, and says `killed`; a live or ended run is refused.
TEST_F(Cli, RecoverTrimsPartialRowsOfAKilledRunAndSaysKilled) {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  ASSERT_GT(child, 0);
  waitpid(child, nullptr, 0);  // a pid that no longer runs
  const fs::path run = dir / "killed";
  fs::create_directories(run / "cam.rgb");
  write_file(run / "metrics.json", "{\"experiment\": \"x\", \"status\": \"running\", \"pid\": " +
                                       std::to_string(child) + "}\n");
  write_file(run / "c.value.csv", "time [s],value\n0,1\n0.001,2\n0.00");
  write_file(run / "cam.rgb" / "index.csv", "time [s],frame,file\n0,1,000001.png\n");
  write_file(dir / "outside.csv", "a,b\n1,");
  fs::create_symlink(dir / "outside.csv", run / "link.csv");
  CliResult r = cli({"recover", "killed"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "c.value.csv: 4 bytes of a partial last row removed\nkilled: status killed (1 file "
            "trimmed)\n");
  EXPECT_EQ(read_file(run / "c.value.csv"), "time [s],value\n0,1\n0.001,2\n");
  EXPECT_EQ(read_file(run / "cam.rgb" / "index.csv"), "time [s],frame,file\n0,1,000001.png\n");
  EXPECT_EQ(read_file(dir / "outside.csv"), "a,b\n1,");  // not followed
  const auto m = metrics("killed");
  EXPECT_EQ(m["status"], "killed");
  EXPECT_FALSE(m.contains("pid"));
  EXPECT_EQ(m["recovered"].size(), 1u);
  // Ended: nothing to recover. Running (this process's pid): refused.
  r = cli({"recover", "killed"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ended (killed): nothing to recover"), std::string::npos) << r.err;
  write_file(run / "metrics.json",
             "{\"status\": \"running\", \"pid\": " + std::to_string(getpid()) + "}\n");
  r = cli({"recover", "killed"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is still running"), std::string::npos) << r.err;
  // Another machine's run; a folder another process holds (its lock).
  write_file(run / "metrics.json", "{\"status\": \"running\", \"pid\": " + std::to_string(child) +
                                       ", \"host\": \"elsewhere\"}\n");
  r = cli({"recover", "killed/"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ran on host 'elsewhere': recover it there"), std::string::npos) << r.err;
  write_file(run / "metrics.json",
             "{\"status\": \"running\", \"pid\": " + std::to_string(child) + "}\n");
  const int held = ::open(run.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  r = cli({"recover", "killed"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is in use by a somasim run"), std::string::npos) << r.err;
  ::close(held);
  for (const char* bad : {"nowhere", "outside.csv"})
    EXPECT_EQ(cli({"recover", bad}, dir, false).code, 2) << bad;
}

TEST_F(Cli, UsageErrorsAreBadInput) {
  CliResult r = cli({}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "error: A subcommand is required\nRun with --help for more information.\n");
  r = cli({"run", "exp.yaml", "--seed", "x"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "error: --seed: expected an integer in [0, 18446744073709551615], got 'x'\n");
  for (const char* seed : {"-1", "18446744073709551616", "1e3", "+5"}) {
    r = cli({"run", "exp.yaml", "--seed", seed}, dir);
    EXPECT_EQ(r.code, 2) << seed;
    EXPECT_EQ(r.err, std::string("error: --seed: expected an integer in [0, "
                                 "18446744073709551615], got '") +
                         seed + "'\n");
  }
}

TEST_F(Cli, PluginsListsTheTestPlugins) {
  const CliResult r = cli({"plugins"}, dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("adder                  Adds its inputs (test plugin).\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("counter                Counts its own steps (test plugin).\n"),
            std::string::npos);
  EXPECT_NE(r.out.find("vector_sink            Takes a vector3 (test plugin).\n"),
            std::string::npos);
  EXPECT_EQ(r.err, "");
}

TEST_F(Cli, PluginsReportsRejectedLibraries) {
  const CliResult r = cli({"--plugin-path", kBadPluginDir, "plugins"}, dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.err, "rejected " + kNoEntryLib +
                       ": no entry point 'somasim_plugin_entry' among its dynamic symbols (is "
                       "SOMASIM_PLUGIN_LIBRARY missing?); not loaded\n"
                       "rejected " +
                       kOldApiLib +
                       ": built for plugin interface 'somasim-plugin-api/0', this somasim needs "
                       "'somasim-plugin-api/6' (rebuild the plugin)\n");
}

TEST_F(Cli, DescribeShowsParamsAndPorts) {
  const CliResult r = cli({"plugins", "describe", "counter"}, dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out,
            "counter\n"
            "  Counts its own steps (test plugin).\n"
            "  library: " +
                kTestPluginLib +
                "\n\n"
                "parameters:\n"
                "  start                    a number, required\n"
                "      first value (required)\n"
                "  increment                a number, default 1, range [-100, 100]\n"
                "      added at each step\n"
                "  mode                     a string, default plain, one of: plain, noisy\n"
                "      noisy adds N(0,1)\n"
                "  stop_after               an integer, default 0, range [0, inf]\n"
                "      request a stop after N steps (0: never)\n"
                "  offset                   a list of 3 numbers [m], default [0, 0, 0]\n"
                "      a vector\n"
                "  fail                     a boolean (true/false), default false\n"
                "      throw a RunError at the 3rd step\n"
                "\n"
                "inputs:\n"
                "  (none)\n"
                "\n"
                "outputs:\n"
                "  value                    scalar (somasim/port_types.hpp)\n"
                "      the count\n"
                "  vector                   vector3 (somasim/port_types.hpp)\n"
                "      offset scaled by the count\n");
  const CliResult adder = cli({"plugins", "describe", "adder"}, dir);
  EXPECT_NE(adder.out.find("inputs:\n"
                           "  a                        scalar (somasim/port_types.hpp)\n"
                           "      first term\n"
                           "  b                        scalar (somasim/port_types.hpp) (optional)\n"
                           "      second term\n"),
            std::string::npos)
      << adder.out;
}

TEST_F(Cli, DescribeUnknownPlugin) {
  const CliResult r = cli({"plugins", "describe", "countr"}, dir);
  EXPECT_EQ(r.code, 2);
  // The search report ends with the build tree's own plugin directory, whose content varies.
  const std::string start =
      "error: unknown plugin 'countr' (did you mean 'counter'?); searched: " + kTestPluginDir +
      " (libsomasim_test_plugins.so); ";
  EXPECT_EQ(r.err.substr(0, start.size()), start);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(Cli, GraphPrintsDot) {
  const CliResult r = cli({"graph", "exp.yaml"}, dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out,
            "digraph \"cli_test\" {\n"
            "  rankdir=LR;\n"
            "  node [shape=record];\n"
            "  \"c\" [label=\"{c|counter|1000 Hz}\"];\n"
            "  \"noise\" [label=\"{noise|counter|1000 Hz}\"];\n"
            "  \"s\" [label=\"{s|adder|1000 Hz}\"];\n"
            "  \"c\" -> \"s\" [label=\"value → a\"];\n"
            "  \"s\" -> \"s\" [label=\"sum → b\", style=dashed];\n"
            "}\n");
}

TEST_F(Cli, ValidateOkAndBad) {
  CliResult r = cli({"validate", "exp.yaml"}, dir);
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "exp.yaml: ok (3 nodes, 0.005 s at 1000 Hz)\n  plugin library loaded: " +
                       kTestPluginLib + "\n");
  write_file(dir / "bad.yaml", R"(experiment: bad
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0, increment: 1000}}
  s: {plugin: adder, inputs: {a: c.valu}}
)");
  r = cli({"validate", "bad.yaml"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "error: 2 errors:\n"
            "  bad.yaml:4:54: node 'c', key 'params.increment': value 1000 is out of range; "
            "expected a number in [-100, 100]\n"
            "  bad.yaml:5:34: node 's', key 'inputs.a': node 'c' (plugin 'counter') has no output "
            "'valu' (did you mean 'value'?); outputs: value, vector\n");
  r = cli({"validate", "exp.yaml", "--set", "nodes.c.params.increment=1000"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --set nodes.c.params.increment=1000: node 'c', key 'params.increment': value "
            "1000 is out of range; expected a number in [-100, 100]\n");
}

TEST_F(Cli, RunCompletes) {
  const CliResult r = cli({"run", "exp.yaml", "--out", "out", "--quiet"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "results: " + (dir / "out").string() + "\n");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(metrics("out")["status"], "completed");
  EXPECT_EQ(read_file(dir / "out" / "c.value.csv"),
            "time [s],value\n0,1\n0.001,2\n0.002,3\n0.003,4\n0.004,5\n");
}

TEST_F(Cli, RunBadInputExitsTwo) {
  CliResult r = cli({"run", "missing.yaml", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "error: experiment file 'missing.yaml' does not exist\n");
  EXPECT_FALSE(fs::exists(dir / "out"));  // nothing was run
  r = cli({"run", "exp.yaml", "--set", "nodes.x.params.start=1"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --set 'nodes.x.params.start=1': no map 'nodes.x' in exp.yaml (did you mean "
            "'c'?)\n");
  r = cli({"run", "exp.yaml", "--set", "seed"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --set 'seed': expected path=value, e.g. nodes.pps.params.threshold=0.2\n");
}

TEST_F(Cli, RunFailureExitsThree) {
  const CliResult r =
      cli({"run", "exp.yaml", "--set", "nodes.c.params.fail=true", "--out", "out", "--quiet"}, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "run failed: node 'c' at t = 0.002 s: deliberate failure\n(outputs flushed to " +
                       (dir / "out").string() + ")\n");
  EXPECT_EQ(metrics("out")["status"], "failed");
  EXPECT_EQ(read_file(dir / "out" / "c.value.csv"), "time [s],value\n0,1\n0.001,2\n");
}

TEST_F(Cli, SetAndSeedApply) {
  // --set a value absent from the file, one in it, and --seed; flags before the file work too.
  CliResult r =
      cli({"run", "--set", "nodes.c.params.increment=0.5", "--set", "nodes.c.params.start=10",
           "--seed", "99", "exp.yaml", "--out", "a", "--quiet"},
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(dir / "a" / "c.value.csv"),
            "time [s],value\n0,10.5\n0.001,11\n0.002,11.5\n0.003,12\n0.004,12.5\n");
  EXPECT_EQ(metrics("a")["seed"], 99);
  const std::string resolved = read_file(dir / "a" / "experiment.resolved.yaml");
  EXPECT_NE(resolved.find("seed: 99\n"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("increment: 0.5\n"), std::string::npos) << resolved;

  r = cli({"run", "exp.yaml", "--seed", "99", "--out", "b", "--quiet"}, dir);
  ASSERT_EQ(r.code, 0);
  r = cli({"run", "exp.yaml", "--seed", "98", "--out", "c", "--quiet"}, dir);
  ASSERT_EQ(r.code, 0);
  EXPECT_EQ(read_file(dir / "a" / "noise.value.csv"), read_file(dir / "b" / "noise.value.csv"));
  EXPECT_NE(read_file(dir / "b" / "noise.value.csv"), read_file(dir / "c" / "noise.value.csv"));
}

// SIGINT (Ctrl-C), SIGTERM and SIGHUP (a closed terminal) all stop the run cleanly: whole CSV
// rows, metrics.json with the status.
TEST_F(Cli, SignalsInterruptAndFlush) {
  write_file(dir / "long.yaml", R"(experiment: long
duration_s: 1.0e7
nodes:
  c: {plugin: counter, rate_hz: 100, params: {start: 0}}
record: [c.value]
)");
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const std::string out = "out" + std::to_string(sig);
    const pid_t pid = spawn_cli({"run", "long.yaml", "--out", out, "--quiet"}, dir);
    // Wait until the run is under way (the handler is installed before log.txt is made), then
    // a little more; the deadline only guards against a hang.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(dir / out / "log.txt") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ASSERT_EQ(kill(pid, sig), 0);
    const CliResult r = wait_cli(pid, dir);
    EXPECT_EQ(r.code, 130) << r.err << " signal " << sig;
    EXPECT_EQ(r.err, "interrupted: outputs flushed to " + (dir / out).string() + "\n");
    const auto m = metrics(out);
    EXPECT_EQ(m["status"], "interrupted");
    EXPECT_EQ(m["stop_reason"], "interrupted");
    EXPECT_GT(m["sim_time_s"].get<double>(), 0.0);
    const std::string csv = read_file(dir / out / "c.value.csv");
    ASSERT_GT(csv.size(), std::string("time [s],value\n").size());
    EXPECT_EQ(csv.back(), '\n');  // the last row is complete
  }
}

}  // namespace
}  // namespace somasim::test

namespace somasim::test {
namespace {

TEST(PpsConvert, IniToJsonAndBack) {
  TempDir dir;
  write_file(dir / "in.ini",
             "[right_hand]\nmodality 2D\nnTaxels 1\next (-0.1 0.2 0 1.2)\nbinsNum (2 1)\n"
             "101 (1 2) (3 4)\n");
  CliResult r = cli({"pps", "convert", "in.ini", "map.json"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "in.ini -> map.json: right_hand (1 taxels)\n");
  EXPECT_NE(r.err.find("note: in.ini holds no taxel geometry"), std::string::npos) << r.err;
  r = cli({"pps", "convert", "map.json", "out.ini"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(dir / "out.ini"),
            "[right_hand]\nmodality 2D\nnTaxels 1\next (-0.1 0.2 0 1.2)\nbinsNum (2 1)\n"
            "101 (1 2) (3 4)\n");
  r = cli({"pps", "convert", "missing.ini", "x.json"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "error: missing.ini: cannot open for reading\n");
}

}  // namespace
}  // namespace somasim::test
