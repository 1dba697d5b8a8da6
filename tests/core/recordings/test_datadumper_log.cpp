// yarpdatadumper logs: both stamp layouts, the time line (gaps, dropped lines), image logs and
// every malformed input refused with FILE:LINE:COLUMN and what was expected.
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "somasim/error.hpp"
#include "somasim/recordings/datadumper_log.hpp"
#include "somasim/recordings/replay_cursor.hpp"

using namespace somasim::recordings;
namespace fs = std::filesystem;

namespace {

class LogFolder {
 public:
  explicit LogFolder(const std::string& type, const std::string& data) {
    static int counter = 0;
    dir_ = fs::temp_directory_path() /
           ("somasim_dump_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir_);
    if (!type.empty())
      std::ofstream(dir_ / "info.log")
          << "Type: " << type << ";\n[1.0] /icub/left_arm/state:o [connected]\n";
    std::ofstream(dir_ / "data.log") << data;
  }
  ~LogFolder() { fs::remove_all(dir_); }
  fs::path data() const { return dir_ / "data.log"; }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

std::string error_of(const LogFolder& f, const DumpReadOptions& options = {}) {
  try {
    read_datadumper_log(f.data(), options);
  } catch (const somasim::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DatadumperLog, ReadsBottleLinesAndTheirTimeLine) {
  // 10 Hz with one 1 s gap; an empty line and an empty content (a Bottle with nothing).
  std::string data;
  double t = 100.0;
  for (int i = 0; i < 20; ++i) {
    data += std::to_string(i) + " " + std::to_string(t) + " " + (i == 3 ? "" : "1.5 -2 (3)") + "\n";
    t += i == 9 ? 1.0 : 0.1;
    if (i == 5) data += "\n";
  }
  LogFolder f("Bottle", data);
  const DatadumperLog log = read_datadumper_log(f.data());
  EXPECT_EQ(log.content, DumpContent::kBottle);
  EXPECT_EQ(log.ports, std::vector<std::string>{"/icub/left_arm/state:o"});
  ASSERT_EQ(log.entries.size(), 20u);
  EXPECT_EQ(log.entries[0].seq, 0);
  EXPECT_DOUBLE_EQ(log.entries[0].stamp_s, 100.0);
  EXPECT_EQ(log.entries[0].content, "1.5 -2 (3)");
  EXPECT_EQ(log.entries[0].content_column, 14);
  EXPECT_EQ(log.entries[3].content, "");
  EXPECT_EQ(log.entries[7].line, 9);  // after the blank line
  EXPECT_NEAR(log.timeline.median_step_s, 0.1, 1e-6);
  ASSERT_EQ(log.timeline.gaps.size(), 1u);
  EXPECT_EQ(log.timeline.gaps[0].line, 12);
  EXPECT_NEAR(log.timeline.gaps[0].to_s - log.timeline.gaps[0].from_s, 1.0, 1e-6);
  EXPECT_NE(describe_timeline(log).find("20 messages over 2.800 s (median 10.0 Hz); 1 gap: 1.000 s "
                                        "before line 12; 0 lines dropped"),
            std::string::npos)
      << describe_timeline(log);
}

TEST(DatadumperLog, ReceiveAndSendStamps) {
  LogFolder f("Bottle", "-1 10.5 9.0 1 2\n-1 10.6 9.2 3 4\n");
  DumpReadOptions options;
  options.columns = StampColumns::kReceiveAndSend;
  EXPECT_DOUBLE_EQ(read_datadumper_log(f.data(), options).entries[1].stamp_s, 10.6);
  options.stamp = ReplayStamp::kSend;
  const DatadumperLog log = read_datadumper_log(f.data(), options);
  EXPECT_DOUBLE_EQ(log.entries[1].stamp_s, 9.2);
  EXPECT_EQ(log.entries[1].content, "3 4");
  options.columns = StampColumns::kReceive;
  EXPECT_EQ(error_of(f, options),
            "replaying by the sender's stamps needs logs dumped with both stamps (stamp columns "
            "'receive_send')");
}

TEST(DatadumperLog, BackwardsStampsRefusedOrDropped) {
  LogFolder f("Bottle", "1 5.0 a\n2 5.1 b\n3 5.05 c\n4 5.2 d\n");
  EXPECT_EQ(error_of(f),
            f.data().string() +
                ":3:3: time stamp 5.050000 is earlier than 5.100000 on line 2 (stamps "
                "must not go backwards; backwards_stamps: drop leaves such lines out)");
  DumpReadOptions options;
  options.backwards = BackwardsStamps::kDrop;
  const DatadumperLog log = read_datadumper_log(f.data(), options);
  ASSERT_EQ(log.entries.size(), 3u);
  EXPECT_EQ(log.entries[2].content, "d");
  ASSERT_EQ(log.timeline.reversals.size(), 1u);
  EXPECT_EQ(log.timeline.reversals[0].line, 3);
  EXPECT_EQ(log.timeline.reversals[0].previous_line, 2);
}

TEST(DatadumperLog, MalformedLinesAreLocated) {
  struct Case {
    std::string data;
    std::string message;  // after "DATA.LOG:"
  };
  const Case cases[] = {
      {"1 2.0 x\nabc 2.1 y\n", "2:1: expected a packet id (an integer, -1 for none), got 'abc'"},
      {"1 2.0 x\n  7\n", "2:4: expected a time stamp (a number of seconds), got ''"},
      {"1 2.0 x\n2 2.x1 y\n", "2:3: expected a time stamp (a number of seconds), got '2.x1'"},
      {"1 inf x\n", "1:3: a time stamp 'inf' is not finite"},
  };
  for (const Case& c : cases) {
    LogFolder f("Bottle", c.data);
    EXPECT_EQ(error_of(f), f.data().string() + ":" + c.message) << c.data;
  }
  LogFolder two("Bottle", "1 2.0 x\n");
  DumpReadOptions options;
  options.columns = StampColumns::kReceiveAndSend;
  EXPECT_EQ(error_of(two, options),
            two.data().string() +
                ":1:7: expected the sender's time stamp (a number of seconds), "
                "got 'x'");
  LogFolder empty("Bottle", "\n\n");
  EXPECT_EQ(error_of(empty), empty.data().string() + ": no messages (an empty log)");
}

TEST(DatadumperLog, InfoLogMustSayWhatTheLogHolds) {
  LogFolder none("", "1 2.0 x\n");
  EXPECT_EQ(error_of(none),
            (none.dir() / "info.log").string() +
                ": missing or unreadable (yarpdatadumper writes it beside data.log; its 'Type:' "
                "line says whether the log holds Bottles or images)");
  LogFolder odd("Sound", "1 2.0 x\n");
  EXPECT_EQ(error_of(odd), (odd.dir() / "info.log").string() +
                               ":1:7: unknown log type 'Sound' (expected Bottle, Image or "
                               "Image:FORMAT)");
}

TEST(DatadumperLog, ImageLogsNameTheirFiles) {
  LogFolder f("Image:ppm", "0 1.0 00000000.ppm [rgb]\n1 1.1 00000001.ppm [rgb]\n");
  std::ofstream(f.dir() / "00000000.ppm") << "P6\n1 1\n255\nabc";
  const std::string missing = (f.dir() / "00000001.ppm").string();
  EXPECT_EQ(error_of(f), f.data().string() + ":2:7: image file '" + missing + "' does not exist (" +
                             missing + ")");
  std::ofstream(f.dir() / "00000001.ppm") << "P6\n1 1\n255\nabc";
  const DatadumperLog log = read_datadumper_log(f.data());
  EXPECT_EQ(log.content, DumpContent::kImage);
  EXPECT_EQ(log.type, "Image:ppm");
  EXPECT_EQ(log.image_file(log.entries[1]), f.dir() / "00000001.ppm");
  LogFolder nameless("Image", "0 1.0\n");
  EXPECT_EQ(error_of(nameless),
            nameless.data().string() + ":1:6: expected an image file name after the time stamp");
}

TEST(ReplayCursor, DeliversEachMessageOnceAtItsTime) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<DumpEntry> entries;
    double stamp = std::uniform_real_distribution<double>(0, 1e9)(rng);
    const int n = std::uniform_int_distribution<int>(1, 50)(rng);
    for (int i = 0; i < n; ++i) {
      DumpEntry e;
      e.line = i + 1;
      e.stamp_s = stamp;
      entries.push_back(e);
      stamp += std::uniform_int_distribution<int>(0, 3)(rng) * 0.01;  // repeats allowed
    }
    const double offset = std::uniform_real_distribution<double>(0, 2)(rng);
    ReplayCursor cursor(entries, offset);
    std::size_t delivered = 0;
    const double dt = std::uniform_real_distribution<double>(0.001, 0.05)(rng);
    for (double t = 0.0; !cursor.done(); t += dt) {
      for (const DumpEntry& e : cursor.advance_to(t)) {
        EXPECT_EQ(static_cast<std::size_t>(e.line), ++delivered);
        EXPECT_LE(cursor.due_time(e), t + 1e-9);
        EXPECT_GT(cursor.due_time(e), t - dt - 1e-6);  // not late by more than a step
      }
      ASSERT_LT(t, 1e4);
    }
    EXPECT_EQ(delivered, entries.size());
    EXPECT_NEAR(cursor.due_time(entries.front()), offset, 1e-6);
  }
}
