// The framework's recorder of CSV-recordable ports: `<dir>/<node>.<port>.csv`, a header row
// (time and the type's columns with units) on the first write, one row per producer step.
#include <cstdio>

#include <fmt/format.h>

#include "somasim/error.hpp"
#include "somasim/port_type.hpp"

namespace somasim {
namespace {

class CsvRecorder final : public PortRecorder {
 public:
  CsvRecorder(const std::filesystem::path& file, const PortTypeInfo& type, const void* value)
      : type_(type), value_(value) {
    out_ = std::fopen(file.c_str(), "w");
    if (!out_) throw RunError("cannot write '" + file.string() + "'");
  }
  ~CsvRecorder() override { flush(); }
  CsvRecorder(const CsvRecorder&) = delete;
  CsvRecorder& operator=(const CsvRecorder&) = delete;

  void write(double time_s) override {
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

  void flush() override {
    if (out_) {
      std::fclose(out_);
      out_ = nullptr;
    }
  }

 private:
  const PortTypeInfo& type_;
  const void* value_;
  std::FILE* out_ = nullptr;
  std::string row_;
  bool header_written_ = false;
};

}  // namespace

std::unique_ptr<PortRecorder> make_csv_recorder(const PortTypeInfo& type, const void* value,
                                                const RecordTarget& target) {
  return std::make_unique<CsvRecorder>(target.dir / (target.stem + ".csv"), type, value);
}

}  // namespace somasim
