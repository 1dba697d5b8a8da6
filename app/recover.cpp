#include "recover.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "somasim/error.hpp"
#include "somasim/runner.hpp"
#include "somasim/yaml_text.hpp"

namespace somasim::app {

namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Cuts `file` back to its last newline; returns the bytes removed (0 when it ends whole).
std::uintmax_t trim_partial_row(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) throw RunError("cannot open " + file.string());
  const off_t size = ::lseek(fd, 0, SEEK_END);
  off_t keep = size;
  // Back from the end, a block at a time, to the last newline.
  char block[65536];
  bool found = false;
  while (keep > 0 && !found) {
    const off_t start =
        keep > static_cast<off_t>(sizeof block) ? keep - static_cast<off_t>(sizeof block) : 0;
    const auto want = static_cast<std::size_t>(keep - start);
    if (::pread(fd, block, want, start) != static_cast<ssize_t>(want)) {
      ::close(fd);
      throw RunError("cannot read " + file.string());
    }
    std::size_t i = want;
    while (i > 0 && block[i - 1] != '\n') --i;
    found = i > 0;
    keep = start + static_cast<off_t>(i);
  }
  std::uintmax_t removed = 0;
  if (keep < size) {
    if (::ftruncate(fd, keep) != 0) {
      ::close(fd);
      throw RunError("cannot trim " + file.string());
    }
    removed = static_cast<std::uintmax_t>(size - keep);
  }
  ::close(fd);
  return removed;
}

// The run folder's lock for as long as recover works on it.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir)
      : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW)) {
    if (fd_ < 0) throw InputError(fmt::format("recover: cannot open '{}'", dir.string()));
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
    const int error = errno;
    if (error == EWOULDBLOCK) {
      ::close(fd_);
      throw InputError(fmt::format("recover: '{}' is in use by a somasim run", dir.string()));
    }
    fmt::print(stderr, "warning: cannot lock '{}' ({}); make sure its run has ended\n",
               dir.string(), std::strerror(error));
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() { ::close(fd_); }

 private:
  int fd_;
};

}  // namespace

RecoveryReport recover_run_folder(const fs::path& dir_arg) {
  // "runs/x/" names the folder itself, not a link's target.
  const fs::path dir = dir_arg.filename().empty() ? dir_arg.parent_path() : dir_arg;
  std::error_code ec;
  if (fs::is_symlink(dir, ec) || !fs::is_directory(dir, ec))
    throw InputError(fmt::format("recover: '{}' is not a run folder", dir.string()));
  const fs::path metrics_file = dir / "metrics.json";
  if (!fs::is_regular_file(fs::symlink_status(metrics_file, ec)))
    throw InputError(
        fmt::format("recover: '{}' has no metrics.json: not a run folder", dir.string()));
  nlohmann::ordered_json metrics;
  try {
    metrics = nlohmann::ordered_json::parse(read_text(metrics_file));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("recover: {}: not JSON ({})", metrics_file.string(), e.what()));
  }
  const auto text_of = [&](const char* key) -> std::string {
    const auto it = metrics.is_object() ? metrics.find(key) : metrics.end();
    return it != metrics.end() && it->is_string() ? it->get<std::string>() : "";
  };
  const std::string status = text_of("status");
  if (status != "running")
    throw InputError(fmt::format("recover: '{}' ended ({}): nothing to recover", dir.string(),
                                 status.empty() ? "no status" : status));
  const std::string host = text_of("host");
  if (!host.empty() && host != host_name())
    throw InputError(fmt::format("recover: the run in '{}' ran on host '{}': recover it there",
                                 dir.string(), host));
  const auto pid_it = metrics.find("pid");
  const long long pid =
      pid_it != metrics.end() && pid_it->is_number_integer() ? pid_it->get<long long>() : 0;
  if (pid > 0 && pid <= std::numeric_limits<pid_t>::max() &&
      (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM))
    throw InputError(
        fmt::format("recover: the run in '{}' (process {}) is still running", dir.string(), pid));
  const FolderLock lock(dir);  // a live somasim holds it whatever its pid says
  RecoveryReport report;
  auto it = fs::recursive_directory_iterator(dir, ec);
  for (; !ec && it != fs::end(it); it.increment(ec)) {
    if (it->is_symlink() || !it->is_regular_file() || it->path().extension() != ".csv") continue;
    if (const auto removed = trim_partial_row(it->path()); removed > 0)
      report.trimmed.push_back(fmt::format("{}: {} bytes of a partial last row removed",
                                           fs::relative(it->path(), dir).string(), removed));
  }
  if (ec) throw RunError(fmt::format("recover: cannot list '{}': {}", dir.string(), ec.message()));
  metrics["status"] = "killed";
  metrics["error"] = "the run was killed before it ended; recovered by `somasim recover`";
  metrics["stop_reason"] = metrics["error"];
  metrics["recovered"] = report.trimmed;
  metrics.erase("pid");
  metrics.erase("host");
  write_metrics_file(metrics_file, metrics);
  return report;
}

int cmd_recover(const std::string& dir) {
  const RecoveryReport report = recover_run_folder(dir);
  for (const auto& line : report.trimmed) fmt::print("{}\n", line);
  fmt::print("{}: status killed ({} file{} trimmed)\n", escape_control_bytes(dir),
             report.trimmed.size(), report.trimmed.size() == 1 ? "" : "s");
  return kExitOk;
}

}  // namespace somasim::app
