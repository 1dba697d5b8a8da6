#pragma once
// What the yarp_*_replay plugins share: the log parameters (a config block), reading the log
// with located errors, and the time-line report (log line and metrics).
#include <string>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/recordings/datadumper_log.hpp"
#include "somasim/recordings/replay_cursor.hpp"

namespace somasim::plugins {

/// The `log` parameters of a replay node.
struct ReplayLogParams {
  InputFile log;
  recordings::StampColumns stamp_columns = recordings::StampColumns::kReceive;
  recordings::ReplayStamp replay_stamp = recordings::ReplayStamp::kReceive;
  recordings::BackwardsStamps backwards_stamps = recordings::BackwardsStamps::kError;
  double gap_factor = 5.0;
  double offset_s = 0.0;  // [s]
  template <class V>
  void visit(V& v) {
    v.field("log", log)
        .doc(
            "the yarpdatadumper log's data.log (info.log beside it), relative to the experiment "
            "file");
    v.field("stamp_columns", stamp_columns)
        .doc(
            "time stamps after the packet id: receive (default dump) or receive_send (dumped "
            "with --txTime)");
    v.field("replay_stamp", replay_stamp)
        .doc("the stamp that times the replay: receive, or send (needs receive_send)");
    v.field("backwards_stamps", backwards_stamps)
        .doc(
            "a line stamped earlier than the previous one: error (refuse the log) or drop it "
            "(listed in the report)");
    v.field("gap_factor", gap_factor)
        .at_least(1.0)
        .doc("a step between stamps longer than this many median steps is reported as a gap");
    v.field("offset_s", offset_s)
        .unit("s")
        .at_least(0.0)
        .doc("simulated time of the log's first message (later ones keep their recorded spacing)");
  }
};

/// Reads the log a node's ReplayLogParams name; InputError located at the `log` parameter
/// (with the log's own FILE:LINE:COLUMN) on any problem, or when it holds `expected` content
/// of the other kind.
template <class Config>
recordings::DatadumperLog read_replay_log(NodeContext& ctx, const Config& config,
                                          const ReplayLogParams& params,
                                          recordings::DumpContent expected);

/// Logs the time line (messages, span, gaps, dropped lines) at info level.
void log_timeline(NodeContext& ctx, const recordings::DatadumperLog& log);
/// Reports the replay's metrics: messages, delivered, span_s, median_rate_hz, gaps,
/// longest_gap_s, dropped_lines (each gap and dropped line with its data.log line).
void report_replay(NodeContext& ctx, const recordings::DatadumperLog& log,
                   const recordings::ReplayCursor& cursor);

// Implementation of the template.
recordings::DatadumperLog read_replay_log_at(NodeContext& ctx, const std::string& key,
                                             const ReplayLogParams& params,
                                             recordings::DumpContent expected);
template <class Config>
recordings::DatadumperLog read_replay_log(NodeContext& ctx, const Config& config,
                                          const ReplayLogParams& params,
                                          recordings::DumpContent expected) {
  return read_replay_log_at(ctx, config_key(config, params.log), params, expected);
}

}  // namespace somasim::plugins
