#pragma once
// Runs the `somasim` program from tests: in a temporary folder, stdout/stderr captured.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "test_support.hpp"

extern char** environ;

namespace somasim::test {

inline const std::string kBinary = SOMASIM_BINARY;

struct CliResult {
  int code = -1;  ///< exit code, or 128 + signal
  std::string out, err;
};

// Starts `somasim --plugin-path TEST_PLUGIN_DIR args...` with stdout/stderr to files in `dir`.
inline pid_t spawn_cli(const std::vector<std::string>& args, const TempDir& dir,
                       bool with_plugin_path = true) {
  std::vector<std::string> argv_s = {kBinary};
  if (with_plugin_path) argv_s.insert(argv_s.end(), {"--plugin-path", kTestPluginDir});
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, (dir / "stdout").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, (dir / "stderr").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addchdir_np(&actions, dir.path().c_str());
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, kBinary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(rc, 0) << "cannot start " << kBinary;
  return pid;
}

inline CliResult wait_cli(pid_t pid, const TempDir& dir) {
  int status = 0;
  waitpid(pid, &status, 0);
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_file(dir / "stdout");
  r.err = read_file(dir / "stderr");
  return r;
}

// Runs the program in `dir` (its working directory) and waits for it.
inline CliResult cli(const std::vector<std::string>& args, const TempDir& dir,
                     bool with_plugin_path = true) {
  return wait_cli(spawn_cli(args, dir, with_plugin_path), dir);
}

}  // namespace somasim::test
