// run_experiment: the run folder, failures, re-running the resolved file, determinism.
#include <algorithm>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "somasim/experiment.hpp"
#include "somasim/interrupt.hpp"
#include "somasim/metrics_layout.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/runner.hpp"
#include "somasim/testing/harness.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {
namespace fs = std::filesystem;

const std::string kExperiment = R"(experiment: runner_test
seed: 3
duration_s: 0.01
base_rate_hz: 1000
nodes:
  c: {plugin: counter, rate_hz: 500, params: {start: 0, offset: [1, 0, -1]}}
  noise: {plugin: counter, params: {start: 0, mode: noisy}}
  s: {plugin: adder, inputs: {a: c.value, b: noise.value}}
record: [c.value, c.vector, s.sum]
)";

struct RunResult {
  RunReport report;
  fs::path dir;
};

// Writes `yaml` into `dir`/exp.yaml, loads and runs it into `dir`/`name`.
RunResult run(const TempDir& dir, const std::string& yaml, const std::string& name = "run",
              const LoadOptions& options = {}) {
  const fs::path file = dir / "exp.yaml";
  write_file(file, yaml);
  PluginRegistry registry({kTestPluginDir});
  const Experiment exp = load_experiment_file(file, registry, options);
  RunOptions ro;
  ro.out_dir = dir / name;
  ro.quiet = true;
  return {run_experiment(exp, ro), ro.out_dir};
}

nlohmann::json metrics_of(const fs::path& run_dir) {
  return nlohmann::json::parse(read_file(run_dir / "metrics.json"));
}

TEST(Runner, AFailureOutsideTheNodesStillLeavesMetrics) {
  // log.txt cannot be created (a folder is in its place): the run fails before any node runs,
  // and says why in the report and in metrics.json.
  TempDir dir;
  fs::create_directories(dir / "run" / "log.txt");
  const RunResult r = run(dir, kExperiment);
  EXPECT_EQ(r.report.status, RunStatus::Failed);
  EXPECT_NE(r.report.error.find("log.txt"), std::string::npos) << r.report.error;
  const auto m = metrics_of(r.dir);
  EXPECT_EQ(m["status"], "failed");
  EXPECT_EQ(m["error"], r.report.error);
  EXPECT_EQ(m["experiment"], "runner_test");
}

TEST(Runner, RunFolderHasEveryOutput) {
  TempDir dir;
  const RunResult r = run(dir, kExperiment);
  EXPECT_EQ(r.report.status, RunStatus::Completed);
  EXPECT_EQ(r.report.error, "");
  EXPECT_EQ(r.report.stop_reason, "duration reached");
  for (const char* f : {"experiment.resolved.yaml", "log.txt", "metrics.json", "c.value.csv",
                        "c.vector.csv", "s.sum.csv"})
    EXPECT_TRUE(fs::exists(r.dir / f)) << f;
  // c runs at 500 Hz: 5 rows over 10 ms, time column first.
  EXPECT_EQ(read_file(r.dir / "c.value.csv"),
            "time [s],value\n0,1\n0.002,2\n0.004,3\n0.006,4\n0.008,5\n");
  EXPECT_EQ(read_file(r.dir / "c.vector.csv"),
            "time [s],x,y,z\n0,1,0,-1\n0.002,2,0,-2\n0.004,3,0,-3\n0.006,4,0,-4\n0.008,5,0,-5\n");
  const std::string sum = read_file(r.dir / "s.sum.csv");
  EXPECT_EQ(sum.substr(0, sum.find('\n')), "time [s],value");
  EXPECT_EQ(std::count(sum.begin(), sum.end(), '\n'), 11);  // header + 10 ticks

  const auto m = metrics_of(r.dir);
  EXPECT_EQ(m["experiment"], "runner_test");
  EXPECT_EQ(m["status"], "completed");
  EXPECT_EQ(m["error"], "");
  EXPECT_EQ(m["stop_reason"], "duration reached");
  EXPECT_EQ(m["seed"], 3);
  EXPECT_DOUBLE_EQ(m["sim_time_s"].get<double>(), 0.01);
  EXPECT_TRUE(m["wall_time_s"].is_number());
  EXPECT_TRUE(m["real_time_factor"].is_number());
  EXPECT_EQ(m["versions"]["somasim"], "0.1.0");
  EXPECT_EQ(m["versions"]["plugin_interface"], "somasim-plugin-api/6");
  EXPECT_TRUE(m["versions"]["compiler"].is_string());
  // Nothing is written twice: the run's own keys, then one section per node.
  for (const auto& [key, value] : m.items())
    EXPECT_TRUE(key == "nodes" || std::find(kRunMetricKeys.begin(), kRunMetricKeys.end(), key) !=
                                      kRunMetricKeys.end())
        << key;
  EXPECT_EQ(m["nodes"]["c"]["steps"], 5);
  EXPECT_EQ(m["nodes"]["noise"]["steps"], 10);
  EXPECT_EQ(m["nodes"]["c"]["final"], 5.0);
  // Flat names: a name reported by two nodes is qualified by the node.
  EXPECT_EQ(find_metric(m, "c.steps"), 5);
  EXPECT_EQ(find_metric(m, "noise.steps"), 10);
  EXPECT_EQ(find_metric(m, "s.final"), m["nodes"]["s"]["final"]);
  EXPECT_FALSE(find_metric(m, "steps").has_value());

  const std::string log = read_file(r.dir / "log.txt");
  EXPECT_NE(log.find("experiment 'runner_test'"), std::string::npos) << log;
  EXPECT_NE(log.find("completed (duration reached)"), std::string::npos) << log;
}

TEST(Runner, StopRequestedByANode) {
  TempDir dir;
  const RunResult r = run(dir, R"(experiment: t
duration_s: 10
nodes:
  c: {plugin: counter, params: {start: 0, stop_after: 3}}
record: [c.value]
)");
  EXPECT_EQ(r.report.status, RunStatus::Completed);
  EXPECT_EQ(r.report.stop_reason, "node 'c': counted enough");
  EXPECT_EQ(read_file(r.dir / "c.value.csv"), "time [s],value\n0,1\n0.001,2\n0.002,3\n");
  EXPECT_EQ(metrics_of(r.dir)["stop_reason"], "node 'c': counted enough");
}

TEST(Runner, FailingNodeFailsTheRunAndFlushesOutputs) {
  TempDir dir;
  const RunResult r = run(dir, R"(experiment: t
duration_s: 1
nodes:
  c: {plugin: counter, params: {start: 0, fail: true}}
  s: {plugin: adder, inputs: {a: c.value}}
record: [c.value, s.sum]
)");
  const std::string error = "node 'c' at t = 0.002 s: deliberate failure";
  EXPECT_EQ(r.report.status, RunStatus::Failed);
  EXPECT_EQ(r.report.error, error);
  const auto m = metrics_of(r.dir);
  EXPECT_EQ(m["status"], "failed");
  EXPECT_EQ(m["error"], error);
  EXPECT_EQ(m["stop_reason"], error);
  EXPECT_EQ(find_metric(m, "steps"), 3);  // finish() still ran and reported
  // Every row up to the failure (ticks 0 and 1) is flushed.
  EXPECT_EQ(read_file(r.dir / "c.value.csv"), "time [s],value\n0,1\n0.001,2\n");
  EXPECT_EQ(read_file(r.dir / "s.sum.csv"), "time [s],value\n0,1\n0.001,2\n");
  EXPECT_NE(read_file(r.dir / "log.txt").find("run failed: " + error), std::string::npos);
}

TEST(Runner, InterruptStopsTheRunWithStatusInterrupted) {
  TempDir dir;
  request_interrupt();
  const RunResult r = run(dir, kExperiment);
  clear_interrupt();
  EXPECT_EQ(r.report.status, RunStatus::Interrupted);
  EXPECT_EQ(r.report.stop_reason, "interrupted");
  EXPECT_EQ(metrics_of(r.dir)["status"], "interrupted");
  EXPECT_TRUE(fs::exists(r.dir / "c.value.csv"));
}

TEST(Runner, ResolvedFileRerunsToIdenticalOutputs) {
  TempDir dir;
  LoadOptions options;
  options.overrides = {{"nodes.c.params.increment", "0.5"}};
  options.seed = 42;
  const RunResult first = run(dir, kExperiment, "first", options);
  ASSERT_EQ(first.report.status, RunStatus::Completed);
  const std::string resolved = read_file(first.dir / "experiment.resolved.yaml");

  PluginRegistry registry({kTestPluginDir});
  const Experiment again = load_experiment_file(first.dir / "experiment.resolved.yaml", registry);
  EXPECT_EQ(again.seed, 42u);
  EXPECT_EQ(again.resolved_yaml(), resolved);  // resolving is idempotent
  RunOptions ro;
  ro.out_dir = dir / "second";
  ro.quiet = true;
  ASSERT_EQ(run_experiment(again, ro).status, RunStatus::Completed);
  for (const char* csv : {"c.value.csv", "c.vector.csv", "s.sum.csv"})
    EXPECT_EQ(read_file(dir / "second" / csv), read_file(first.dir / csv)) << csv;
  EXPECT_EQ(read_file(dir / "second" / "c.value.csv"),
            "time [s],value\n0,0.5\n0.002,1\n0.004,1.5\n0.006,2\n0.008,2.5\n");
}

TEST(Runner, SameSeedGivesByteIdenticalOutputs) {
  TempDir dir;
  const RunResult a = run(dir, kExperiment, "a");
  const RunResult b = run(dir, kExperiment, "b");
  for (const char* csv : {"c.value.csv", "c.vector.csv", "s.sum.csv"})
    EXPECT_EQ(read_file(a.dir / csv), read_file(b.dir / csv)) << csv;
  auto ma = metrics_of(a.dir), mb = metrics_of(b.dir);
  for (auto* m : {&ma, &mb}) {
    m->erase("wall_time_s");
    m->erase("real_time_factor");
  }
  EXPECT_EQ(ma, mb);
  EXPECT_EQ(read_file(a.dir / "experiment.resolved.yaml"),
            read_file(b.dir / "experiment.resolved.yaml"));

  LoadOptions other_seed;
  other_seed.seed = 4;
  const RunResult c = run(dir, kExperiment, "c", other_seed);
  EXPECT_NE(read_file(c.dir / "s.sum.csv"), read_file(a.dir / "s.sum.csv"));
  EXPECT_EQ(read_file(c.dir / "c.value.csv"), read_file(a.dir / "c.value.csv"));  // not noisy
}

}  // namespace
// NodeContext::is_read: an output is read when another node's input is wired to it (delayed or
// not) or the experiment records it; the harness counts every output as read.
TEST(Runner, OutputsAreReadWhenWiredOrRecorded) {
  TempDir dir;
  const RunResult r =
      run(dir,
          "experiment: probe\nduration_s: 0.1\n"
          "nodes:\n"
          "  probe: {plugin: read_probe}\n"
          "  sink: {plugin: adder, inputs: {a: probe.a, b: {from: probe.a, delayed: "
          "true}}}\n"
          "record: [probe.c]\n");
  ASSERT_EQ(r.report.status, RunStatus::Completed) << r.report.error;
  const auto m = metrics_of(r.dir)["nodes"]["probe"];
  EXPECT_EQ(m["read_a"], true);
  EXPECT_EQ(m["read_b"], false);
  EXPECT_EQ(m["read_c"], true);
  somasim::testing::Harness h("nodes:\n  probe: {plugin: read_probe}\n", {kTestPluginDir});
  h.finish();
  EXPECT_EQ(h.metric("probe", "read_b"), true);
}

}  // namespace somasim::test
