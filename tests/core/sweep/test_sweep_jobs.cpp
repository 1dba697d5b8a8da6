// Checking a sweep's jobs with the experiment loader, the output root's manifest, run states.
#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/plugin_registry.hpp"
#include "somasim/sweep/collect.hpp"
#include "somasim/sweep/hash.hpp"
#include "somasim/sweep/jobs.hpp"
#include "somasim/sweep/run_folder.hpp"
#include "test_support.hpp"

namespace somasim::sweep {
namespace {
namespace fs = std::filesystem;

const std::string kExperiment = R"(experiment: jobs_test
duration_s: 0.005
nodes:
  c: {plugin: counter, params: {start: 0}}
)";

class SweepJobs : public ::testing::Test {
 protected:
  void SetUp() override { test::write_file(dir / "exp.yaml", kExperiment); }
  SweepSpec spec(const std::string& axes) {
    return load_sweep_text("sweep: j\nexperiment: exp.yaml\nseeds: [1, 2]\naxes:\n" + axes,
                           "s.yaml", dir.path());
  }
  std::string resolve_error(const std::string& axes) {
    const SweepSpec s = spec(axes);
    auto jobs = expand_jobs(s);
    try {
      resolve_jobs(s, jobs, registry);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  test::TempDir dir;
  PluginRegistry registry{{test::kTestPluginDir}};
};

TEST_F(SweepJobs, EveryJobIsLoadedWithItsOverridesAndSeed) {
  const SweepSpec s = spec("  nodes.c.params.increment: [1, 2]\n");
  auto jobs = expand_jobs(s);
  const BaseExperiment base = resolve_jobs(s, jobs, registry);
  EXPECT_EQ(base.name, "jobs_test");
  EXPECT_EQ(base.hash.substr(0, 8), "fnv1a64:");
  EXPECT_EQ(jobs[1].resolved_seed, 2u);
  // Seeds and values change the resolved experiment; each job's hash is its own.
  EXPECT_NE(jobs[0].resolved_hash, jobs[1].resolved_hash);
  EXPECT_NE(jobs[0].resolved_hash, jobs[2].resolved_hash);
  EXPECT_EQ(jobs_tsv(jobs),
            "index\tfolder\tseed\toverrides\n"
            "0\truns/0000\t1\tnodes.c.params.increment=1\n"
            "1\truns/0001\t2\tnodes.c.params.increment=1\n"
            "2\truns/0002\t1\tnodes.c.params.increment=2\n"
            "3\truns/0003\t2\tnodes.c.params.increment=2\n");
}

TEST_F(SweepJobs, AJobTheLoaderRejectsIsLocatedInTheSweepFile) {
  const std::string exp = (dir / "exp.yaml").string();
  EXPECT_EQ(resolve_error("  nodes.c.params.incremnt: [1, 2]\n"),
            "s.yaml:5:29: key 'axes.nodes.c.params.incremnt': --set "
            "'nodes.c.params.incremnt=1': 'nodes.c.params.incremnt' does not exist in " +
                exp + " and is not a key that can be set there (did you mean 'increment'?)");
  EXPECT_EQ(resolve_error("  nodes.c.params.increment: [1, 500]\n"),
            "s.yaml:5:33: key 'axes.nodes.c.params.increment': --set "
            "nodes.c.params.increment=500: node 'c', key 'params.increment': value 500 is out "
            "of range; expected a number in [-100, 100]");
  test::write_file(dir / "exp.yaml", "experiment: jobs_test\nnodes: {}\n");
  EXPECT_EQ(resolve_error("  nodes.c.params.increment: [1]\n"),
            "s.yaml:2:13: key 'experiment': " + exp +
                ":1:1: key 'duration_s': missing required key (expected a number)");
}

TEST_F(SweepJobs, AnOutputFolderOfAnotherBaseExperimentIsRefused) {
  const SweepSpec s = spec("  nodes.c.params.increment: [1]\n");
  auto jobs = expand_jobs(s);
  const BaseExperiment base = resolve_jobs(s, jobs, registry);
  const fs::path root = dir / "out";
  prepare_output_root(root, s, base, jobs, true);
  EXPECT_TRUE(fs::exists(root / "sweep.json"));
  EXPECT_TRUE(fs::exists(root / "jobs.tsv"));
  prepare_output_root(root, s, base, jobs, false);  // the same sweep again: fine
  const BaseExperiment other{"other", "fnv1a64:0000000000000001"};
  try {
    prepare_output_root(root, s, other, jobs, true);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "output folder '" + root.string() +
                  "' holds runs of another base experiment: its sweep.json names 'jobs_test' (" +
                  base.hash + "), this sweep runs 'other' (fnv1a64:0000000000000001, from " +
                  (dir / "exp.yaml").string() + "); choose another --out or remove that folder");
  }
  test::write_file(dir / "stray" / "x", "");
  fs::create_directories(dir / "stray");
  test::write_file(dir / "stray" / "x", "");
  EXPECT_THROW(prepare_output_root(dir / "stray", s, base, jobs, true), InputError);
}

TEST_F(SweepJobs, RunStateComesFromMetricsResolvedExperimentAndManifest) {
  Job job;
  job.resolved_hash = content_hash("resolved text");
  const fs::path run = dir / "run";
  fs::create_directories(run);
  EXPECT_EQ(run_state(run, job), RunState::kRedo);  // empty: never ran
  test::write_file(run / "experiment.resolved.yaml", "resolved text");
  test::write_file(run / "metrics.json", R"({"status": "completed"})");
  EXPECT_EQ(run_state(run, job), RunState::kCompleted);
  test::write_file(run / "metrics.json", R"({"status": "comp)");  // half-written
  EXPECT_EQ(run_state(run, job), RunState::kRedo);
  test::write_file(run / "metrics.json", R"({"status": "failed"})");
  test::write_file(run / "manifest.json",
                   R"({"exit_status": "failed", "resolved_hash": ")" + job.resolved_hash + "\"}");
  EXPECT_EQ(run_state(run, job), RunState::kFailed);
  test::write_file(run / "manifest.json", R"({"exit_status": "interrupted", "resolved_hash": ")" +
                                              job.resolved_hash + "\"}");
  EXPECT_EQ(run_state(run, job), RunState::kRedo);
  test::write_file(run / "metrics.json", R"({"status": "completed"})");
  test::write_file(run / "experiment.resolved.yaml", "another experiment");
  EXPECT_EQ(run_state(run, job), RunState::kRedo);
}

TEST(SweepHash, IsFnv1a64) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(content_hash("a"), "fnv1a64:af63dc4c8601ec8c");
}

TEST(SweepCollect, WallClockColumnsAreNamed) {
  for (const char* c : {"wall_time_s", "real_time_factor", "host", "filter_step_ms"})
    EXPECT_TRUE(is_wall_clock_column(c)) << c;
  for (const char* c : {"sim_time_s", "ms", "events", "status"})
    EXPECT_FALSE(is_wall_clock_column(c)) << c;
}

}  // namespace
}  // namespace somasim::sweep
