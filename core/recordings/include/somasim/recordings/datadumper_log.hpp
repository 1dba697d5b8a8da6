#pragma once
/// @file
/// yarpdatadumper logs: one folder per recorded port with `info.log` (what was recorded:
/// `Type: Bottle;` or `Type: Image;` / `Type: Image:ppm;`, then one line per connection) and
/// `data.log`, one line per message:
/// @code
///   [packet id] [time stamp] [content]              e.g.  14739 1412842922.723273 (1 2 3)
///   [packet id] [receive stamp] [send stamp] [content]    (dumped with --txTime)
/// @endcode
/// The content of a Bottle log is the Bottle's text (yarp_bottle.hpp); that of an image log is
/// the image file's name, relative to the folder (e.g. `00000012.ppm`, optionally followed by
/// a bracketed pixel type such as `[rgb]`). The packet id is -1 when the sender gave none.
/// Time stamps are seconds (usually Unix time).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "somasim/name_table.hpp"

namespace somasim::recordings {

/// What a log holds.
enum class DumpContent : std::uint8_t { kBottle, kImage };

/// Which time stamps a data.log line carries after the packet id.
enum class StampColumns : std::uint8_t {
  kReceive,         ///< one: the dumper's receive time
  kReceiveAndSend,  ///< two: receive time, then the sender's time (--txTime)
};
inline constexpr NamedValue<StampColumns> kStampColumnsNames[] = {
    {StampColumns::kReceive, "receive"}, {StampColumns::kReceiveAndSend, "receive_send"}};
constexpr std::span<const NamedValue<StampColumns>> name_table(StampColumns) {
  return kStampColumnsNames;
}

/// Which of the stamps orders and times the replay (with kReceiveAndSend).
enum class ReplayStamp : std::uint8_t { kReceive, kSend };
inline constexpr NamedValue<ReplayStamp> kReplayStampNames[] = {{ReplayStamp::kReceive, "receive"},
                                                                {ReplayStamp::kSend, "send"}};
constexpr std::span<const NamedValue<ReplayStamp>> name_table(ReplayStamp) {
  return kReplayStampNames;
}

/// What to do with a line whose stamp is earlier than the previous line's.
enum class BackwardsStamps : std::uint8_t {
  kError,  ///< refuse the log, naming the line
  kDrop,   ///< leave the line out (listed in the time line's report)
};
inline constexpr NamedValue<BackwardsStamps> kBackwardsStampsNames[] = {
    {BackwardsStamps::kError, "error"}, {BackwardsStamps::kDrop, "drop"}};
constexpr std::span<const NamedValue<BackwardsStamps>> name_table(BackwardsStamps) {
  return kBackwardsStampsNames;
}

/// How to read a log.
struct DumpReadOptions {
  StampColumns columns = StampColumns::kReceive;
  ReplayStamp stamp = ReplayStamp::kReceive;  ///< only kReceive when columns == kReceive
  BackwardsStamps backwards = BackwardsStamps::kError;
  /// A step between consecutive stamps longer than this many times the median step is a gap.
  double gap_factor = 5.0;
};

/// One message of the log.
struct DumpEntry {
  int line = 0;            ///< 1-based line in data.log
  std::int64_t seq = -1;   ///< packet id (-1: none)
  double stamp_s = 0.0;    ///< the replay stamp (DumpReadOptions::stamp) [s]
  int stamp_column = 0;    ///< 1-based column of that stamp in the line
  std::string content;     ///< the rest of the line, leading and trailing spaces removed
  int content_column = 0;  ///< 1-based column of `content` in the line
};

/// A step between two consecutive kept entries longer than gap_factor × the median step.
struct StampGap {
  int line = 0;  ///< the line after the gap
  double from_s = 0.0, to_s = 0.0;
};

/// A line left out because its stamp went backwards (BackwardsStamps::kDrop).
struct StampReversal {
  int line = 0;           ///< the dropped line
  int previous_line = 0;  ///< the kept line it is earlier than
  double stamp_s = 0.0, previous_s = 0.0;
};

/// The time line of a log, for the replay's report.
struct DumpTimeline {
  double first_s = 0.0, last_s = 0.0;  ///< first and last kept stamp [s]
  double median_step_s = 0.0;          ///< median step between kept stamps [s] (0: < 2 entries)
  std::vector<StampGap> gaps;
  std::vector<StampReversal> reversals;
};

/// A whole log, read and checked.
struct DatadumperLog {
  std::filesystem::path folder;  ///< the folder of data.log
  DumpContent content = DumpContent::kBottle;
  std::string type;                ///< the `Type:` of info.log, e.g. "Bottle", "Image:ppm"
  std::vector<std::string> ports;  ///< ports named in info.log's connection lines
  std::vector<DumpEntry> entries;  ///< in file order, non-decreasing stamps
  DumpTimeline timeline;

  /// The image file of an entry of an image log (the first word of its content).
  std::filesystem::path image_file(const DumpEntry& entry) const;
};

/// Reads the log whose data.log is `data_log` (info.log beside it). Throws InputError naming
/// "FILE:LINE:COLUMN" and what was expected: info.log missing or without a `Type:` line or of
/// an unknown type; a data.log line without a packet id, a stamp, or (with kReceiveAndSend) the
/// second stamp; a non-finite stamp; a stamp earlier than the previous line's
/// (BackwardsStamps::kError); an image log line naming no file or a file that is missing or not
/// a regular file; a log without a single message. Bottle contents are not parsed here.
DatadumperLog read_datadumper_log(const std::filesystem::path& data_log,
                                  const DumpReadOptions& options = {});

/// A one-paragraph report of the time line: messages, span, median rate, gaps and dropped lines
/// (at most `max_listed` of each listed with their lines).
std::string describe_timeline(const DatadumperLog& log, std::size_t max_listed = 5);

}  // namespace somasim::recordings
