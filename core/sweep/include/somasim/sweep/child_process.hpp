#pragma once
/// @file
/// Starting and waiting for child processes (each sweep run is one), POSIX only.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace somasim::sweep {

/// How a child ended.
struct ChildExit {
  int code = -1;            ///< exit code, or -1 when killed by a signal
  int signal = 0;           ///< the signal that killed it, or 0
  std::string str() const;  ///< "exit 3" or "killed by signal 11 (Segmentation fault)"
};

/// Starts `argv` (argv[0] is the program path) with stdout and stderr appended to `log` and
/// stdin from /dev/null. `own_process_group`: the child leads a process group of its own, so a
/// Ctrl-C on the terminal reaches only the caller, which decides what the child gets.
/// Throws RunError when it cannot be started.
pid_t start_child(const std::vector<std::string>& argv, const std::filesystem::path& log,
                  bool own_process_group);

/// The path of the running executable (/proc/self/exe).
std::filesystem::path self_executable();

/// `name` found on $PATH (an executable file), or empty.
std::filesystem::path find_on_path(const std::string& name);

/// Runs `argv`, returns its exit and its stdout; stderr goes to `err`.
ChildExit run_capture(const std::vector<std::string>& argv, std::string& out, std::string& err);

/// Decodes a waitpid() status.
ChildExit decode_wait_status(int status);

}  // namespace somasim::sweep
