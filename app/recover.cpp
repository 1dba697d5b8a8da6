#include "recover.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "somasim/error.hpp"
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
  char c = '\n';
  // Back from the end to the last newline (rows are short: read a byte at a time).
  while (keep > 0 && ::pread(fd, &c, 1, keep - 1) == 1 && c != '\n') --keep;
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

}  // namespace

RecoveryReport recover_run_folder(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_symlink(dir, ec) || !fs::is_directory(dir, ec))
    throw InputError(fmt::format("recover: '{}' is not a run folder", dir.string()));
  const fs::path metrics_file = dir / "metrics.json";
  if (!fs::is_regular_file(fs::symlink_status(metrics_file, ec)))
    throw InputError(
        fmt::format("recover: '{}' has no metrics.json: not a run folder", dir.string()));
  nlohmann::json metrics;
  try {
    metrics = nlohmann::json::parse(read_text(metrics_file));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("recover: {}: not JSON ({})", metrics_file.string(), e.what()));
  }
  const std::string status = metrics.is_object() ? metrics.value("status", "") : "";
  if (status != "running")
    throw InputError(fmt::format("recover: '{}' ended ({}): nothing to recover", dir.string(),
                                 status.empty() ? "no status" : status));
  const long pid = metrics.value("pid", 0L);
  if (pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM))
    throw InputError(
        fmt::format("recover: the run in '{}' (process {}) is still running", dir.string(), pid));
  // The run's lock: a live somasim holds it whatever its pid says.
  const int lock = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock >= 0 && ::flock(lock, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    ::close(lock);
    throw InputError(fmt::format("recover: '{}' is in use by a somasim run", dir.string()));
  }
  RecoveryReport report;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_symlink() || !it->is_regular_file() || it->path().extension() != ".csv") continue;
    if (const auto removed = trim_partial_row(it->path()); removed > 0)
      report.trimmed.push_back(fmt::format("{}: {} bytes of a partial last row removed",
                                           fs::relative(it->path(), dir).string(), removed));
  }
  metrics["status"] = "killed";
  metrics["error"] = "the run was killed before it ended; recovered by `somasim recover`";
  metrics["stop_reason"] = metrics["error"];
  metrics["recovered"] = report.trimmed;
  metrics.erase("pid");
  const fs::path tmp = dir / "metrics.json.tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << metrics.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    if (!out) throw RunError("cannot write " + tmp.string());
  }
  fs::rename(tmp, metrics_file);
  if (lock >= 0) ::close(lock);
  return report;
}

int cmd_recover(const std::string& dir) {
  const RecoveryReport report = recover_run_folder(dir);
  for (const auto& line : report.trimmed) fmt::print("{}\n", line);
  fmt::print("{}: status killed ({} file{} trimmed)\n", dir, report.trimmed.size(),
             report.trimmed.size() == 1 ? "" : "s");
  return kExitOk;
}

}  // namespace somasim::app
