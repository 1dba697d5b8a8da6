// body_schema_filter `distribute: mpi` under a real mpirun (OpenMPI): configs/body_schema_reaching
// shortened to two short movements (plus a compared filter). Two ranks must write the same
// outputs as one process, byte for byte (wall-clock fields aside); more ranks than particles is
// a located error; a failure on one rank must end the job instead of hanging the other ranks.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment_runner.hpp"
#include "somasim/metrics_layout.hpp"

namespace fs = std::filesystem;
using somasim::testing::read_file;

namespace {

struct Result {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs a shell command; a hung MPI job is killed after 120 s (exit code 137) so that the test
// fails with a message before the ctest TIMEOUT.
Result shell(const std::string& command) {
  Result r;
  const std::string full = "timeout -s KILL 120 " + command + " 2>&1";
  std::FILE* pipe = ::popen(full.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

// A private folder for this test's run folders and the ranks' scratch folders (TMPDIR).
fs::path work_dir(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("somasim-mpi-test-" + tag);
  fs::remove_all(dir);
  fs::create_directories(dir / "tmp");
  return dir;
}

// `somasim run` of the shortened experiment with M = `particles` and a compared filter of 15;
// `extra` are further arguments (e.g. --set).
std::string somasim_run(const fs::path& out, int particles = 40, const std::string& extra = "") {
  std::string cmd = std::string(SOMASIM_BINARY) + " run " + SOMASIM_SOURCE_DIR +
                    "/configs/body_schema_reaching.yaml --quiet --out " + out.string();
  for (const char* set :
       {"nodes.reach.params.targets=[-0.006,0.007,0.258,44.2,-78.7,-66.4]",
        "nodes.reach.params.starts_per_target=2", "nodes.reach.params.repetitions=1",
        "nodes.reach.params.open_loop_frames=20", "nodes.reach.params.closed_loop_frames=5",
        "nodes.filter.params.render_threads=1", "nodes.filter.params.compare_particles=[15]",
        "nodes.filter.params.evaluate_frame=20", "nodes.filter.params.distribute=mpi"})
    cmd += std::string(" --set '") + set + "'";
  return cmd + " --set nodes.filter.params.particles=" + std::to_string(particles) + " " + extra;
}

std::string mpirun(const fs::path& tmp, int ranks) {
  return "env TMPDIR=" + tmp.string() + " " + SOMASIM_MPIEXEC +
         " --allow-run-as-root --oversubscribe -n " + std::to_string(ranks) + " ";
}

// Every regular file under `dir`, relative to it.
std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir));
  std::sort(out.begin(), out.end());
  return out;
}

// `m` without wall-clock fields (wall_time_s, real_time_factor, *_ms), at any depth.
void drop_clock_fields(nlohmann::json& m) {
  for (auto it = m.begin(); it != m.end();) {
    const std::string& key = it.key();
    const bool clock = key == "wall_time_s" || key == "real_time_factor" ||
                       (key.size() > 3 && key.compare(key.size() - 3, 3, "_ms") == 0);
    if (clock) {
      it = m.erase(it);
      continue;
    }
    if (it->is_object()) drop_clock_fields(*it);
    ++it;
  }
}

nlohmann::json metrics_without_clock(const fs::path& file) {
  nlohmann::json m = nlohmann::json::parse(read_file(file));
  drop_clock_fields(m);
  return m;
}

}  // namespace

TEST(BodySchemaMpi, TwoRanksWriteTheSameOutputsAsOneProcess) {
  const fs::path dir = work_dir("same");
  const Result one = shell(somasim_run(dir / "one"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const Result two = shell(mpirun(dir / "tmp", 2) + somasim_run(dir / "two"));
  ASSERT_EQ(two.exit_code, 0) << two.output;
  // Only rank 0 reports its run folder; rank 1's scratch folder is gone.
  EXPECT_EQ(two.output, "results: " + (dir / "two").string() + "\n");
  for (const auto& e : fs::directory_iterator(dir / "tmp"))
    EXPECT_NE(e.path().filename().string().rfind("somasim-rank", 0), 0u) << e.path();

  const std::vector<fs::path> files = files_under(dir / "one");
  ASSERT_EQ(files, files_under(dir / "two"));
  const nlohmann::json m = nlohmann::json::parse(read_file(dir / "two" / "metrics.json"));
  ASSERT_EQ(m["status"], "completed") << m["error"];
  EXPECT_EQ(somasim::find_metric(m, "filter_frames"), 2 * 26);
  EXPECT_TRUE(somasim::find_metric(m, "filter_gather_ms"));
  EXPECT_TRUE(somasim::find_metric(m, "particles_15_estimation_error_mm"));
  EXPECT_GT(read_file(dir / "two" / "body_schema_filter.csv").size(), 1000u);
  for (const fs::path& f : files) {
    // log.txt has time stamps; the particle figure plots the step time (wall clock).
    if (f == "log.txt" || f == "figures/body_schema_particles.png" ||
        f == "figures/body_schema_particles.svg")
      continue;
    if (f == "metrics.json")
      EXPECT_EQ(metrics_without_clock(dir / "one" / f).dump(1),
                metrics_without_clock(dir / "two" / f).dump(1));
    else
      EXPECT_TRUE(read_file(dir / "one" / f) == read_file(dir / "two" / f)) << f;
  }
  fs::remove_all(dir);
}

TEST(BodySchemaMpi, MoreRanksThanParticlesIsALocatedError) {
  const fs::path dir = work_dir("ranks");
  const Result r = shell(mpirun(dir / "tmp", 3) + somasim_run(dir / "out", 2));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("error: --set nodes.filter.params.particles=2: node 'filter', key "
                          "'params.particles': distribute: mpi over 3 ranks needs at least one "
                          "particle per rank, but this filter has 2 particles (launch at most 2 "
                          "ranks, or use more particles)\n"),
            std::string::npos)
      << r.output;
  fs::remove_all(dir);
}

// Rank 1 fails in its first filter step (its hypothesis links are out of view) while rank 0
// would wait for its likelihoods: the job must end with rank 1's error, not hang.
TEST(BodySchemaMpi, AFailingRankEndsTheJobInsteadOfHangingTheOthers) {
  const fs::path dir = work_dir("fail");
  const Result r =
      shell(mpirun(dir / "tmp", 1) + somasim_run(dir / "rank0") + " : -n 1 " +
            somasim_run(dir / "rank1", 40, "--set 'nodes.filter.params.links=[l_upper_arm]'"));
  EXPECT_EQ(r.exit_code, 3) << r.output;  // rank 1's exit code: the run failed
  EXPECT_NE(r.output.find("run failed: node 'filter' at t = 1.9 s: body_schema_filter: movement "
                          "0: the hypothesis links (l_upper_arm) are not visible"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("results:"), std::string::npos) << r.output;
  fs::remove_all(dir);
}
