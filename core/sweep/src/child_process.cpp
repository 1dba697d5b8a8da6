#include "somasim/sweep/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "somasim/error.hpp"

extern char** environ;

namespace somasim::sweep {
namespace fs = std::filesystem;

std::string ChildExit::str() const {
  if (signal != 0) return fmt::format("killed by signal {} ({})", signal, ::strsignal(signal));
  return fmt::format("exit {}", code);
}

ChildExit decode_wait_status(int status) {
  ChildExit e;
  if (WIFEXITED(status)) e.code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
  return e;
}

namespace {

// The environment for a child run: this process's, without the variables by which mpirun and
// srun mark an MPI rank (OMPI_*, PMIX_*, PMI_*). A sweep started inside an MPI launch would
// otherwise make every child `somasim run` join that job as a rank (app/mpi_session.hpp).
std::vector<char*> child_environment() {
  std::vector<char*> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string_view v(*e);
    if (v.starts_with("OMPI_") || v.starts_with("PMIX_") || v.starts_with("PMI_")) continue;
    env.push_back(*e);
  }
  env.push_back(nullptr);
  return env;
}

pid_t spawn(const std::vector<std::string>& args, posix_spawn_file_actions_t* actions,
            const posix_spawnattr_t* attr = nullptr) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  argv.reserve(copy.size() + 1);
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  std::vector<char*> env = child_environment();
  const int rc = ::posix_spawn(&pid, copy.front().c_str(), actions, attr, argv.data(), env.data());
  if (rc != 0)
    throw RunError(fmt::format("cannot start '{}': {}", args.front(), std::strerror(rc)));
  return pid;
}

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

pid_t start_child(const std::vector<std::string>& argv, const fs::path& log,
                  bool own_process_group) {
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (own_process_group) {
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  try {
    const pid_t pid = spawn(argv, &actions, &attr);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    return pid;
  } catch (...) {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    throw;
  }
}

fs::path self_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw RunError("cannot find the running executable (/proc/self/exe): " + ec.message());
  return p;
}

fs::path find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = (dir.empty() ? fs::path(".") : fs::path(dir)) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

ChildExit run_capture(const std::vector<std::string>& argv, std::string& out, std::string& err) {
  char out_name[] = "/tmp/somasim-capture-out-XXXXXX";
  char err_name[] = "/tmp/somasim-capture-err-XXXXXX";
  const int out_fd = ::mkstemp(out_name);
  const int err_fd = ::mkstemp(err_name);
  if (out_fd < 0 || err_fd < 0) throw RunError("cannot create a temporary file");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_fd, 1);
  posix_spawn_file_actions_adddup2(&actions, err_fd, 2);
  pid_t pid = -1;
  try {
    pid = spawn(argv, &actions);
  } catch (...) {
    posix_spawn_file_actions_destroy(&actions);
    ::close(out_fd), ::close(err_fd), ::unlink(out_name), ::unlink(err_name);
    throw;
  }
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ::close(out_fd), ::close(err_fd);
  out = slurp(out_name);
  err = slurp(err_name);
  ::unlink(out_name), ::unlink(err_name);
  return decode_wait_status(status);
}

}  // namespace somasim::sweep
