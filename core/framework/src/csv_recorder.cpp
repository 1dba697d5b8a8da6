// The framework's recorder of CSV-recordable ports: `<dir>/<node>.<port>.csv`, a header row
// (time and the type's columns with units) on the first write, one row per producer step.
// Rows reach the file whole: they are gathered in memory and written by one write() call per
// batch of complete rows, so a run killed at any moment leaves a file that ends with a complete
// row. A failed write (a full disk) is a RunError naming the file, and the file is cut back to
// the last complete row that reached it.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/port_type.hpp"

namespace somasim {
namespace {

constexpr std::size_t kBatchBytes = 64 * 1024;  // rows held before they are written

class CsvRecorder final : public PortRecorder {
 public:
  CsvRecorder(const std::filesystem::path& file, const PortTypeInfo& type, const void* value)
      : file_(file), type_(type), value_(value) {
    fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw RunError(fmt::format("cannot write '{}': {}", file.string(), std::strerror(errno)));
  }
  ~CsvRecorder() override {
    try {
      flush();
    } catch (const std::exception&) {  // reported by the flush at the end of the run
    }
    close_file();
  }
  CsvRecorder(const CsvRecorder&) = delete;
  CsvRecorder& operator=(const CsvRecorder&) = delete;

  void write(double time_s) override {
    if (fd_ < 0) return;
    if (!header_written_) {
      pending_ += "time [s]";
      for (const auto& c : type_.csv_columns(value_)) {
        pending_ += ',';
        pending_ += c;
      }
      pending_ += '\n';
      header_written_ = true;
    }
    pending_ += fmt::format("{}", time_s);
    type_.csv_write(value_, pending_);
    pending_ += '\n';
    if (pending_.size() >= kBatchBytes) write_pending();
  }

  void flush() override {
    if (fd_ < 0) return;
    write_pending();
    close_file();
  }

 private:
  // Writes the pending complete rows; on failure cuts the file back to what was written whole
  // before and throws.
  void write_pending() {
    std::size_t done = 0;
    while (done < pending_.size()) {
      const ssize_t n = ::write(fd_, pending_.data() + done, pending_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string why = n < 0 ? std::strerror(errno) : "nothing written";
        // Keep the whole rows that reached the file, cut the partial one.
        const std::size_t last_newline =
            done == 0 ? std::string::npos : pending_.rfind('\n', done - 1);
        const std::size_t kept =
            committed_ + (last_newline == std::string::npos ? 0 : last_newline + 1);
        const int cut = ::ftruncate(fd_, static_cast<off_t>(kept));
        close_file();
        pending_.clear();
        throw RunError(fmt::format(
            "cannot write '{}': {} (kept the {} bytes of whole rows that reached it{})",
            file_.string(), why, kept, cut == 0 ? "" : "; could not cut off the partial row"));
      }
      done += static_cast<std::size_t>(n);
    }
    committed_ += pending_.size();
    pending_.clear();
  }

  void close_file() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

  std::filesystem::path file_;
  const PortTypeInfo& type_;
  const void* value_;
  int fd_ = -1;
  std::string pending_;        // complete rows not yet written
  std::size_t committed_ = 0;  // bytes of complete rows in the file
  bool header_written_ = false;
};

}  // namespace

std::unique_ptr<PortRecorder> make_csv_recorder(const PortTypeInfo& type, const void* value,
                                                const RecordTarget& target) {
  return std::make_unique<CsvRecorder>(target.dir / (target.stem + ".csv"), type, value);
}

}  // namespace somasim
