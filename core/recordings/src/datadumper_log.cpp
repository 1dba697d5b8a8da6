#include "somasim/recordings/datadumper_log.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

#include "somasim/config.hpp"
#include "somasim/error.hpp"

namespace somasim::recordings {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// The next space-separated word of `line` from `pos` (advanced past it); empty at the end.
std::string_view next_word(std::string_view line, std::size_t& pos, std::size_t& start) {
  while (pos < line.size() && is_space(line[pos])) ++pos;
  start = pos;
  while (pos < line.size() && !is_space(line[pos])) ++pos;
  return line.substr(start, pos - start);
}

std::string located(const std::filesystem::path& file, int line, std::size_t column) {
  return fmt::format("{}:{}:{}", file.string(), line, column + 1);
}

struct InfoLog {
  DumpContent content = DumpContent::kBottle;
  std::string type;
  std::vector<std::string> ports;
};

InfoLog read_info_log(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format(
        "{}: missing or unreadable (yarpdatadumper writes it beside data.log; its 'Type:' line "
        "says whether the log holds Bottles or images)",
        file.string()));
  InfoLog info;
  bool typed = false;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string_view text(line);
    if (text.rfind("Type:", 0) == 0) {
      std::string type(text.substr(5));
      type.erase(
          std::remove_if(type.begin(), type.end(), [](char c) { return is_space(c) || c == ';'; }),
          type.end());
      if (type == "Bottle") {
        info.content = DumpContent::kBottle;
      } else if (type.rfind("Image", 0) == 0) {
        info.content = DumpContent::kImage;
      } else {
        throw InputError(
            fmt::format("{}:{}:7: unknown log type '{}' (expected Bottle, Image or "
                        "Image:FORMAT)",
                        file.string(), number, type));
      }
      info.type = type;
      typed = true;
    } else if (const auto close = text.find("] ");
               !text.empty() && text[0] == '[' && close != std::string_view::npos) {
      std::size_t pos = close + 2, start = 0;
      const std::string_view port = next_word(text, pos, start);
      if (!port.empty() &&
          std::find(info.ports.begin(), info.ports.end(), port) == info.ports.end())
        info.ports.emplace_back(port);
    }
  }
  if (!typed)
    throw InputError(
        fmt::format("{}: no 'Type:' line (expected 'Type: Bottle;' or "
                    "'Type: Image;')",
                    file.string()));
  return info;
}

double parse_stamp(std::string_view word, const std::filesystem::path& file, int line,
                   std::size_t column, const char* what) {
  double v = 0.0;
  const auto [p, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (word.empty() || ec != std::errc() || p != word.data() + word.size())
    throw InputError(fmt::format("{}: expected {} (a number of seconds), got '{}'",
                                 located(file, line, column), what, word));
  if (!std::isfinite(v))
    throw InputError(
        fmt::format("{}: {} '{}' is not finite", located(file, line, column), what, word));
  return v;
}

DumpEntry parse_line(std::string_view text, const std::filesystem::path& file, int line,
                     const DumpReadOptions& options) {
  DumpEntry e;
  e.line = line;
  std::size_t pos = 0, start = 0;
  const std::string_view seq = next_word(text, pos, start);
  const auto [p, ec] = std::from_chars(seq.data(), seq.data() + seq.size(), e.seq);
  if (seq.empty() || ec != std::errc() || p != seq.data() + seq.size())
    throw InputError(fmt::format("{}: expected a packet id (an integer, -1 for none), got '{}'",
                                 located(file, line, start), seq));
  const std::string_view rx = next_word(text, pos, start);
  const double receive = parse_stamp(rx, file, line, start, "a time stamp");
  e.stamp_s = receive;
  e.stamp_column = static_cast<int>(start) + 1;
  if (options.columns == StampColumns::kReceiveAndSend) {
    const std::string_view tx = next_word(text, pos, start);
    const double send = parse_stamp(tx, file, line, start, "the sender's time stamp");
    if (options.stamp == ReplayStamp::kSend) {
      e.stamp_s = send;
      e.stamp_column = static_cast<int>(start) + 1;
    }
  }
  while (pos < text.size() && is_space(text[pos])) ++pos;
  std::size_t end = text.size();
  while (end > pos && is_space(text[end - 1])) --end;
  e.content = std::string(text.substr(pos, end - pos));
  e.content_column = static_cast<int>(pos) + 1;
  return e;
}

void check_image(const DatadumperLog& log, const DumpEntry& e, const std::filesystem::path& file) {
  if (e.content.empty())
    throw InputError(
        fmt::format("{}: expected an image file name after the time stamp",
                    located(file, e.line, static_cast<std::size_t>(e.content_column - 1))));
  const std::filesystem::path image = log.image_file(e);
  if (const std::string why = input_file_problem(image); !why.empty())
    throw InputError(
        fmt::format("{}: image file '{}' {}",
                    located(file, e.line, static_cast<std::size_t>(e.content_column - 1)),
                    image.string(), why));
}

DumpTimeline make_timeline(const std::vector<DumpEntry>& entries, double gap_factor) {
  DumpTimeline t;
  t.first_s = entries.front().stamp_s;
  t.last_s = entries.back().stamp_s;
  if (entries.size() < 2) return t;
  std::vector<double> steps;
  steps.reserve(entries.size() - 1);
  for (std::size_t i = 1; i < entries.size(); ++i)
    steps.push_back(entries[i].stamp_s - entries[i - 1].stamp_s);
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                   sorted.end());
  t.median_step_s = sorted[sorted.size() / 2];
  if (t.median_step_s > 0.0)
    for (std::size_t i = 0; i < steps.size(); ++i)
      if (steps[i] > gap_factor * t.median_step_s)
        t.gaps.push_back({entries[i + 1].line, entries[i].stamp_s, entries[i + 1].stamp_s});
  return t;
}

}  // namespace

std::filesystem::path DatadumperLog::image_file(const DumpEntry& entry) const {
  std::size_t pos = 0, start = 0;
  return folder / std::string(next_word(entry.content, pos, start));
}

DatadumperLog read_datadumper_log(const std::filesystem::path& data_log,
                                  const DumpReadOptions& options) {
  if (options.stamp == ReplayStamp::kSend && options.columns != StampColumns::kReceiveAndSend)
    throw InputError(
        "replaying by the sender's stamps needs logs dumped with both stamps "
        "(stamp columns 'receive_send')");
  DatadumperLog log;
  log.folder = data_log.parent_path();
  InfoLog info = read_info_log(log.folder / "info.log");
  log.content = info.content;
  log.type = std::move(info.type);
  log.ports = std::move(info.ports);

  if (const std::string why = input_file_problem(data_log); !why.empty())
    throw InputError(fmt::format("{}: {}", data_log.string(), why));
  std::ifstream in(data_log);
  if (!in) throw InputError(fmt::format("{}: cannot be read", data_log.string()));
  std::string line;
  int number = 0;
  std::vector<StampReversal> reversals;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    DumpEntry e = parse_line(line, data_log, number, options);
    if (!log.entries.empty() && e.stamp_s < log.entries.back().stamp_s) {
      const DumpEntry& prev = log.entries.back();
      if (options.backwards == BackwardsStamps::kError)
        throw InputError(fmt::format(
            "{}: time stamp {:.6f} is earlier than {:.6f} on line {} (stamps must not go "
            "backwards; backwards_stamps: drop leaves such lines out)",
            located(data_log, number, static_cast<std::size_t>(e.stamp_column - 1)), e.stamp_s,
            prev.stamp_s, prev.line));
      reversals.push_back({number, prev.line, e.stamp_s, prev.stamp_s});
      continue;
    }
    if (log.content == DumpContent::kImage) check_image(log, e, data_log);
    log.entries.push_back(std::move(e));
  }
  if (log.entries.empty())
    throw InputError(fmt::format("{}: no messages (an empty log)", data_log.string()));
  log.timeline = make_timeline(log.entries, options.gap_factor);
  log.timeline.reversals = std::move(reversals);
  return log;
}

std::string describe_timeline(const DatadumperLog& log, std::size_t max_listed) {
  const DumpTimeline& t = log.timeline;
  std::string s =
      fmt::format("{} messages over {:.3f} s", log.entries.size(), t.last_s - t.first_s);
  if (t.median_step_s > 0.0) s += fmt::format(" (median {:.1f} Hz)", 1.0 / t.median_step_s);
  s += fmt::format("; {} gap{}", t.gaps.size(), t.gaps.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < t.gaps.size() && i < max_listed; ++i)
    s += fmt::format("{} {:.3f} s before line {}", i ? "," : ":", t.gaps[i].to_s - t.gaps[i].from_s,
                     t.gaps[i].line);
  if (t.gaps.size() > max_listed) s += ", ...";
  s += fmt::format("; {} line{} dropped for a backwards stamp", t.reversals.size(),
                   t.reversals.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < t.reversals.size() && i < max_listed; ++i)
    s += fmt::format("{} line {}", i ? "," : ":", t.reversals[i].line);
  if (t.reversals.size() > max_listed) s += ", ...";
  return s;
}

}  // namespace somasim::recordings
