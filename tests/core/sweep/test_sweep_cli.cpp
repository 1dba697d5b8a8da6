// `somasim sweep`: expand, run (workers, skips, failures, retries), run-one, slurm, collect.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "somasim/sweep/collect.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {
namespace fs = std::filesystem;

const std::string kExperiment = R"(experiment: sweep_cli
seed: 1
duration_s: 0.005
nodes:
  c: {plugin: counter, params: {start: 0}}
  noise: {plugin: counter, params: {start: 0, mode: noisy}}
record: [c.value]
)";

// Six runs: three (increment, fail) pairs x two seeds; the last pair fails at its third step.
const std::string kSweep = R"(sweep: s
experiment: exp.yaml
seeds: [1, 2]
mode: zip
axes:
  nodes.c.params.increment: [1, 2, 3]
  nodes.c.params.fail: [false, false, true]
summary: {metric: noise.final, against: nodes.c.params.increment}
)";

class SweepCli : public ::testing::Test {
 protected:
  void SetUp() override {
    unsetenv("SOMASIM_PLUGIN_PATH");
    write_file(dir / "exp.yaml", kExperiment);
    write_file(dir / "sweep.yaml", kSweep);
  }
  nlohmann::json json(const std::string& file) const {
    return nlohmann::json::parse(read_file(dir / file));
  }
  // sweep.csv without the wall-clock columns (sweep::is_wall_clock_column).
  std::string deterministic_csv(const std::string& root) const {
    std::stringstream in(read_file(dir / root / "sweep.csv"));
    std::string line, out;
    std::vector<bool> keep;
    while (std::getline(in, line)) {
      std::vector<std::string> cells;
      std::stringstream cs(line);
      for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
      if (keep.empty())
        for (const auto& c : cells) keep.push_back(!sweep::is_wall_clock_column(c));
      for (std::size_t i = 0; i < cells.size() && i < keep.size(); ++i)
        if (keep[i]) out += cells[i] + ",";
      out += "\n";
    }
    return out;
  }
  TempDir dir;
};

TEST_F(SweepCli, HelpNamesEveryVerb) {
  const CliResult r = cli({"sweep", "--help"}, dir, false);
  EXPECT_EQ(r.code, 0);
  for (const char* verb : {"expand", "run", "run-one", "slurm", "collect"})
    EXPECT_NE(r.out.find(verb), std::string::npos) << verb;
  EXPECT_NE(cli({"--help"}, dir, false).out.find("sweep"), std::string::npos);
}

TEST_F(SweepCli, ExpandWritesTheJobList) {
  const CliResult r = cli({"sweep", "expand", "sweep.yaml", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "6 runs: out/jobs.tsv\n");
  EXPECT_EQ(read_file(dir / "out/jobs.tsv"),
            "index\tfolder\tseed\toverrides\n"
            "0\truns/0000\t1\tnodes.c.params.increment=1\tnodes.c.params.fail=false\n"
            "1\truns/0001\t2\tnodes.c.params.increment=1\tnodes.c.params.fail=false\n"
            "2\truns/0002\t1\tnodes.c.params.increment=2\tnodes.c.params.fail=false\n"
            "3\truns/0003\t2\tnodes.c.params.increment=2\tnodes.c.params.fail=false\n"
            "4\truns/0004\t1\tnodes.c.params.increment=3\tnodes.c.params.fail=true\n"
            "5\truns/0005\t2\tnodes.c.params.increment=3\tnodes.c.params.fail=true\n");
  // The default output folder is runs/sweeps/NAME.
  EXPECT_EQ(cli({"sweep", "expand", "sweep.yaml"}, dir).out, "6 runs: runs/sweeps/s/jobs.tsv\n");
}

// A seed soak: no axes, one run per seed, each seed's row in sweep.csv.
TEST_F(SweepCli, ASeedSoakRunsOncePerSeedAndCollects) {
  write_file(dir / "soak.yaml",
             "sweep: soak\nexperiment: exp.yaml\nseeds: {from: 3, to: 5}\n"
             "set: {nodes.c.params.increment: 2}\n");
  CliResult r = cli({"sweep", "run", "soak.yaml", "-j", "2", "--out", "soak"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("sweep soak: 3 runs: 3 completed"), std::string::npos) << r.out;
  r = cli({"sweep", "collect", "soak"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  std::stringstream csv(read_file(dir / "soak/sweep.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("index,folder,seed,", 0), 0u) << header;
  std::vector<std::string> seeds;  // the first three columns of each row
  while (std::getline(csv, line)) {
    std::size_t end = 0;
    for (int comma = 0; comma < 3; ++comma) end = line.find(',', end) + 1;
    seeds.push_back(line.substr(0, end - 1));
  }
  EXPECT_EQ(seeds, (std::vector<std::string>{"0,runs/0000,3", "1,runs/0001,4", "2,runs/0002,5"}));
}

TEST_F(SweepCli, RunSkipsCompletedRunsReportsFailuresAndCollects) {
  CliResult r = cli({"sweep", "run", "sweep.yaml", "-j", "2", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "sweep s: 6 runs in out (0 already completed, 6 to run, 2 workers)");
  EXPECT_NE(r.out.find("sweep s: 6 runs: 4 completed (0 skipped as already completed), 2 failed\n"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.err,
            "failed: runs/0004: node 'c' at t = 0.002 s: deliberate failure (log: "
            "out/logs/0004.log)\n"
            "failed: runs/0005: node 'c' at t = 0.002 s: deliberate failure (log: "
            "out/logs/0005.log)\n");
  const nlohmann::json ok = json("out/runs/0002/manifest.json");
  EXPECT_EQ(ok["exit_status"], "completed");
  EXPECT_EQ(ok["exit_code"], 0);
  EXPECT_EQ(ok["seed"], 1);
  EXPECT_EQ(ok["overrides"]["nodes.c.params.increment"], "2");
  EXPECT_EQ(ok["plugin_libraries"][0]["path"], kTestPluginLib);
  for (const char* key :
       {"resolved_hash", "somasim_version", "git_revision", "host", "wall_time_s", "started_at"})
    EXPECT_TRUE(ok.contains(key)) << key;
  EXPECT_EQ(json("out/runs/0004/manifest.json")["exit_status"], "failed");
  EXPECT_EQ(json("out/runs/0004/manifest.json")["exit_code"], 3);

  // Again: the completed runs are skipped, the failed ones only reported.
  r = cli({"sweep", "run", "sweep.yaml", "-j", "2", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(r.out,
            "sweep s: 6 runs in out (4 already completed, 0 to run, 2 workers)\n"
            "sweep s: 6 runs: 4 completed (4 skipped as already completed), 2 failed\n");
  EXPECT_EQ(r.err,
            "failed: runs/0004: node 'c' at t = 0.002 s: deliberate failure (failed before; not "
            "re-run without --retry-failed)\n"
            "failed: runs/0005: node 'c' at t = 0.002 s: deliberate failure (failed before; not "
            "re-run without --retry-failed)\n");
  // A half-written run (interrupted before metrics.json) is redone.
  fs::remove(dir / "out/runs/0001/metrics.json");
  r = cli({"sweep", "run", "sweep.yaml", "--retry-failed", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "sweep s: 6 runs in out (3 already completed, 3 to run, 1 workers)");
  EXPECT_EQ(json("out/runs/0001/metrics.json")["status"], "completed");

  r = cli({"sweep", "collect", "out"}, dir, false);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "out/sweep.csv: 6 runs (4 completed), 16 columns\n"
            "out/sweep_noise.final.png: noise.final against nodes.c.params.increment, 2 points\n");
  EXPECT_TRUE(fs::exists(dir / "out/sweep_noise.final.png"));
  const std::string csv = read_file(dir / "out/sweep.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "index,folder,seed,nodes.c.params.increment,nodes.c.params.fail,status,c.final,"
            "c.steps,error,noise.final,noise.steps,sim_time_s,stop_reason,host,real_time_factor,"
            "wall_time_s");
  std::stringstream lines(csv);
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[3].substr(0, rows[3].find(",,")), "2,runs/0002,1,2,false,completed,10.0,5");
  EXPECT_EQ(rows[6].substr(0, 78),
            "5,runs/0005,2,3,true,failed,6.0,3,node 'c' at t = 0.002 s: deliberate failure,");

  // Bad figure requests name what exists.
  r = cli({"sweep", "collect", "out", "--metric", "noise.fnal"}, dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --metric 'noise.fnal': no run of this sweep reports it (did you mean "
            "'noise.final'?); metrics: c.final, c.steps, error, noise.final, noise.steps, "
            "sim_time_s, stop_reason, host, real_time_factor, wall_time_s\n");
  r = cli({"sweep", "collect", "out", "--metric", "c.final", "--against", "nodes.c.params.inc"},
          dir, false);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --against 'nodes.c.params.inc': not an axis of this sweep (did you mean "
            "'nodes.c.params.fail'?); expected one of: nodes.c.params.increment, "
            "nodes.c.params.fail\n");

  // The same output folder for another base experiment is refused.
  write_file(dir / "other.yaml",
             "experiment: other\nduration_s: 0.005\nnodes:\n"
             "  c: {plugin: counter, params: {start: 0}}\n");
  write_file(dir / "other_sweep.yaml",
             "sweep: o\nexperiment: other.yaml\naxes: {nodes.c.params.increment: [1]}\n");
  r = cli({"sweep", "run", "other_sweep.yaml", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.substr(0, 98),
            "error: output folder 'out' holds runs of another base experiment: its sweep.json "
            "names 'sweep_cli'");
}

TEST_F(SweepCli, OneAndTwoWorkersGiveTheSameTable) {
  ASSERT_EQ(cli({"sweep", "run", "sweep.yaml", "-j", "1", "--out", "one"}, dir).code, 3);
  ASSERT_EQ(cli({"sweep", "run", "sweep.yaml", "-j", "2", "--out", "two"}, dir).code, 3);
  ASSERT_EQ(cli({"sweep", "collect", "one"}, dir, false).code, 0);
  ASSERT_EQ(cli({"sweep", "collect", "two"}, dir, false).code, 0);
  EXPECT_EQ(deterministic_csv("one"), deterministic_csv("two"));
  EXPECT_NE(read_file(dir / "one/sweep.csv"), read_file(dir / "two/sweep.csv"));  // wall clock
  EXPECT_EQ(deterministic_csv("one").find("wall_time_s"), std::string::npos);
}

TEST_F(SweepCli, RunOneRunsOneJob) {
  CliResult r = cli({"sweep", "run-one", "sweep.yaml", "--index", "2", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, 22), "runs/0002: completed (");
  EXPECT_TRUE(fs::exists(dir / "out/sweep.json"));
  EXPECT_FALSE(fs::exists(dir / "out/runs/0001"));
  r = cli({"sweep", "run-one", "sweep.yaml", "--index", "2", "--out", "out"}, dir);
  EXPECT_EQ(r.out, "runs/0002: already completed (skipped)\n");
  r = cli({"sweep", "run-one", "sweep.yaml", "--index", "4", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_EQ(r.err,
            "failed: runs/0004: node 'c' at t = 0.002 s: deliberate failure (log: "
            "out/logs/0004.log)\n");
  r = cli({"sweep", "run-one", "sweep.yaml", "--index", "6", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "error: --index 6: expected an index in [0, 5] (the sweep has 6 runs)\n");
}

TEST_F(SweepCli, SlurmWritesAnArrayScript) {
  CliResult r = cli({"sweep", "slurm", "sweep.yaml", "--out", "out", "--array-throttle", "2",
                     "--partition", "debug", "--time", "00:10:00", "--sbatch-arg=--mem=1G"},
                    dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const fs::path script = dir / "out/sweep.sbatch";
  EXPECT_EQ(r.out, script.string() + "\n");
  const std::string text = read_file(script);
  const std::string logs = (dir / "out/logs").string();
  EXPECT_EQ(text.substr(0, text.find("# Written")),
            "#!/bin/bash\n#SBATCH --job-name=s\n#SBATCH --array=0-5%2\n#SBATCH --output=" + logs +
                "/%A_%a.out\n#SBATCH --error=" + logs +
                "/%A_%a.err\n#SBATCH --partition=debug\n#SBATCH --time=00:10:00\n#SBATCH "
                "--mem=1G\n");
  EXPECT_NE(text.find("exec '" + kBinary + "' '--plugin-path' '" + kTestPluginDir +
                      "' 'sweep' 'run-one' '" + (dir / "sweep.yaml").string() + "' '--out' '" +
                      (dir / "out").string() + "' --index \"$SLURM_ARRAY_TASK_ID\"\n"),
            std::string::npos)
      << text;
  // Without sbatch on PATH: a clear message, exit 2, the script still written.
  const std::string path = std::getenv("PATH");
  setenv("PATH", dir.path().c_str(), 1);
  r = cli({"sweep", "slurm", "sweep.yaml", "--out", "out", "--submit"}, dir);
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: sbatch not found on PATH: install slurm-client or run on a Slurm login node; "
            "the script is at " +
                script.string() + "\n");
  // Values that would break out of an #SBATCH line: refused before the sweep is set up.
  r = cli({"sweep", "slurm", "sweep.yaml", "--out", "out2", "--partition", "debug\ntouch x"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --partition 'debug\\x0atouch x': \\x0a cannot be written into an #SBATCH "
            "line safely (letters, digits and '._/%+,:=@~-' can)\n");
  EXPECT_FALSE(fs::exists(dir / "out2"));
  r = cli({"sweep", "slurm", "sweep.yaml", "--out", "out\ntouch x"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("the log folder '"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out\ntouch x" / "sweep.sbatch"));
  r = cli({"sweep", "slurm", "sweep.yaml", "--time", "ten minutes"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: --time 'ten minutes': expected a Slurm time limit such as 01:30:00, 90 or "
            "2-00:00:00\n");
}

TEST_F(SweepCli, InterruptStopsLaunchingAndSaysWhatIsLeft) {
  // Runs that would take hours: only the interrupt ends them.
  write_file(dir / "long.yaml",
             "sweep: l\nexperiment: exp.yaml\nset: {duration_s: 100000}\n"
             "axes: {nodes.c.params.increment: [1, 2, 3]}\n");
  const pid_t pid = spawn_cli({"sweep", "run", "long.yaml", "--out", "out"}, dir);
  // Once the first run has its log, its interrupt handler is installed.
  // (A bound, not a timing assertion: a sweep that never starts must not hang the suite.)
  for (int i = 0; i < 3000 && !fs::exists(dir / "out/runs/0000/log.txt"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(pid, SIGINT);
  const CliResult r = wait_cli(pid, dir);
  EXPECT_EQ(r.code, 130);
  EXPECT_EQ(r.err,
            "interrupted: 3 runs left (1 interrupted, 2 not started); run the same command "
            "again to resume\n");
  EXPECT_EQ(json("out/runs/0000/manifest.json")["exit_status"], "interrupted");
  EXPECT_EQ(json("out/runs/0000/metrics.json")["status"], "interrupted");
  EXPECT_FALSE(fs::exists(dir / "out/runs/0001"));
}

TEST_F(SweepCli, BadSweepFilesAreBadInput) {
  write_file(dir / "bad.yaml",
             "sweep: b\nexperiment: exp.yaml\naxes:\n  nodes.c.params.start: []\n");
  const CliResult r = cli({"sweep", "expand", "bad.yaml"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err,
            "error: bad.yaml:4:25: key 'axes.nodes.c.params.start': expected at least one value, "
            "got an empty list\n");
}

}  // namespace
}  // namespace somasim::test

namespace somasim::test {

// A symbolic link planted where a run folder goes (or on the way to it): the sweep refuses to
// run rather than empty the link's target.
TEST_F(SweepCli, LinksPlantedInTheOutputFolderAreNotFollowed) {
  ASSERT_EQ(cli({"sweep", "expand", "sweep.yaml", "--out", "out"}, dir).code, 0);
  fs::create_directories(dir / "precious");
  write_file(dir / "precious/keep.txt", "keep\n");
  fs::create_directories(dir / "out/runs");
  fs::create_directory_symlink(dir / "precious", dir / "out/runs/0003");
  CliResult r = cli({"sweep", "run", "sweep.yaml", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("0003' is a symbolic link inside the sweep's output folder"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir / "precious/keep.txt"));
  r = cli({"sweep", "run-one", "sweep.yaml", "--out", "out", "--index", "3"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(fs::exists(dir / "precious/keep.txt"));
  // A link on the way: the whole runs/ folder.
  fs::remove(dir / "out/runs/0003");
  fs::rename(dir / "out/runs", dir / "out/runs_real");
  fs::create_directory_symlink(dir / "precious", dir / "out/runs");
  r = cli({"sweep", "run", "sweep.yaml", "--out", "out"}, dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(fs::exists(dir / "precious/keep.txt"));
}

}  // namespace somasim::test
