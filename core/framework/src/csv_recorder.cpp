#include <fmt/format.h>

#include "node_runtime.hpp"
#include "somasim/error.hpp"

namespace somasim {

CsvRecorder::CsvRecorder(const std::filesystem::path& file, const PortTypeInfo& type,
                         const void* value)
    : file_(file), type_(type), value_(value) {
  out_ = std::fopen(file.c_str(), "w");
  if (!out_) throw RunError("cannot write '" + file.string() + "'");
}

void CsvRecorder::write(double time_s) {
  if (!header_written_) {
    std::string header = "time [s]";
    for (const auto& c : type_.csv_columns(value_)) header += "," + c;
    std::fputs((header + "\n").c_str(), out_);
    header_written_ = true;
  }
  row_ = fmt::format("{}", time_s);
  type_.csv_write(value_, row_);
  row_ += '\n';
  std::fwrite(row_.data(), 1, row_.size(), out_);
}

void CsvRecorder::flush() {
  if (out_) {
    std::fclose(out_);
    out_ = nullptr;
  }
}

}  // namespace somasim
