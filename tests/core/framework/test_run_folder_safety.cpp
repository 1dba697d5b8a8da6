// What a run folder holds when things go wrong: a second run into a folder in use is refused; a
// run killed with SIGKILL leaves metrics.json saying "running", its log lines, and CSV files that
// end with a whole row; --overwrite does not empty a folder through a symbolic link; a write that
// fails (a file size limit standing in for a full disk) fails the run with the file named and
// whole rows kept.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "test_support.hpp"

namespace somasim::test {
namespace {
namespace fs = std::filesystem;

std::string counter_experiment(double duration_s) {
  return "experiment: safety\nduration_s: " + std::to_string(duration_s) +
         "\nnodes:\n  c: {plugin: counter, params: {start: 0}}\nrecord: [c.value]\n";
}

// Every line of a CSV ends with '\n' and has the header's number of commas.
void expect_whole_rows(const fs::path& csv) {
  const std::string text = read_file(csv);
  ASSERT_FALSE(text.empty()) << csv;
  EXPECT_EQ(text.back(), '\n') << "cut mid-row: ..." << text.substr(text.size() - 40);
  std::istringstream in(text);
  std::string header, line;
  std::getline(in, header);
  const auto commas = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(std::count(line.begin(), line.end(), ','), commas) << "row " << rows << ": " << line;
    ++rows;
  }
  EXPECT_GT(rows, 0);
}

// Waits (bounded: a run that never starts must not hang the suite) until `file` has data.
bool wait_for_data(const fs::path& file) {
  for (int i = 0; i < 600; ++i) {
    std::error_code ec;
    if (fs::file_size(file, ec) > 0 && !ec) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

}  // namespace

TEST(RunFolderSafety, AFolderInUseIsRefusedAndAKilledRunSaysSo) {
  TempDir dir;
  write_file(dir / "long.yaml", counter_experiment(1e6));
  const pid_t pid = spawn_cli({"run", "long.yaml", "--out", "out", "--quiet"}, dir);
  ASSERT_TRUE(wait_for_data(dir / "out/c.value.csv")) << read_file(dir / "stderr");
  // A second run into the same folder, even with --overwrite, while the first runs.
  TempDir other;
  write_file(other / "long.yaml", counter_experiment(1e6));
  const CliResult second =
      cli({"run", "long.yaml", "--out", (dir / "out").string(), "--overwrite"}, other);
  EXPECT_EQ(second.code, 2);
  EXPECT_NE(second.err.find("is in use by another somasim run"), std::string::npos) << second.err;
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  const auto metrics = nlohmann::json::parse(read_file(dir / "out/metrics.json"));
  EXPECT_EQ(metrics["status"], "running");
  EXPECT_EQ(metrics["experiment"], "safety");
  EXPECT_NE(read_file(dir / "out/log.txt").find("experiment 'safety'"), std::string::npos);
  expect_whole_rows(dir / "out/c.value.csv");
  // The lock went with the process.
  write_file(dir / "short.yaml", counter_experiment(0.01));
  const CliResult again = cli({"run", "short.yaml", "--out", "out", "--overwrite"}, dir);
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "out/metrics.json"))["status"], "completed");
}

TEST(RunFolderSafety, OverwriteDoesNotEmptyThroughASymbolicLink) {
  TempDir dir;
  fs::create_directories(dir / "precious");
  write_file(dir / "precious/keep.txt", "keep\n");
  fs::create_directory_symlink(dir / "precious", dir / "link");
  write_file(dir / "exp.yaml", counter_experiment(0.01));
  // Also written with a trailing "/" or "/." (which lstat would resolve through the link).
  for (const char* out : {"link", "link/", "link/."}) {
    const CliResult r = cli({"run", "exp.yaml", "--out", out, "--overwrite"}, dir);
    EXPECT_EQ(r.code, 2) << out;
    EXPECT_NE(r.err.find("is a symbolic link; --overwrite empties only a real folder"),
              std::string::npos)
        << out << ": " << r.err;
    EXPECT_TRUE(fs::exists(dir / "precious/keep.txt")) << out;
  }
}

// A file size limit (ulimit -f, SIGXFSZ ignored) makes writes fail as a full disk does.
TEST(RunFolderSafety, AFailedWriteFailsTheRunAndKeepsWholeRows) {
  TempDir dir;
  write_file(dir / "exp.yaml", counter_experiment(20.0));  // about 20000 rows, > 200 KiB
  const std::string command = "cd '" + dir.path().string() +
                              "' && bash -c 'ulimit -f 64; trap \"\" XFSZ; exec \"$0\" "
                              "--plugin-path \"$1\" run exp.yaml --out out --quiet' '" +
                              kBinary + "' '" + kTestPluginDir + "' > stdout 2> stderr";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << read_file(dir / "stderr");
  const std::string err = read_file(dir / "stderr");
  EXPECT_NE(err.find("cannot write '"), std::string::npos) << err;
  EXPECT_NE(err.find("c.value.csv': File too large"), std::string::npos) << err;
  EXPECT_LE(fs::file_size(dir / "out/c.value.csv"), 64u * 1024u);
  expect_whole_rows(dir / "out/c.value.csv");
  const auto metrics = nlohmann::json::parse(read_file(dir / "out/metrics.json"));
  EXPECT_EQ(metrics["status"], "failed");
}

}  // namespace somasim::test
