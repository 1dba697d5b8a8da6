#include "replay_log.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace somasim::plugins {

recordings::DatadumperLog read_replay_log_at(NodeContext& ctx, const std::string& key,
                                             const ReplayLogParams& params,
                                             recordings::DumpContent expected) {
  if (!params.log.given()) ctx.param_error(key, "expected the path of a data.log");
  recordings::DumpReadOptions options;
  options.columns = params.stamp_columns;
  options.stamp = params.replay_stamp;
  options.backwards = params.backwards_stamps;
  options.gap_factor = params.gap_factor;
  recordings::DatadumperLog log;
  try {
    log = recordings::read_datadumper_log(params.log.path, options);
  } catch (const InputError& e) {
    ctx.param_error(key, e.what());
  }
  if (log.content != expected)
    ctx.param_error(
        key,
        fmt::format("{}: the log holds {} (info.log: 'Type: {}'); this node "
                    "replays {}",
                    params.log.path.string(),
                    log.content == recordings::DumpContent::kImage ? "images" : "Bottles", log.type,
                    expected == recordings::DumpContent::kImage ? "images" : "Bottles"));
  return log;
}

void log_timeline(NodeContext& ctx, const recordings::DatadumperLog& log) {
  ctx.log().info("{}: {}", (log.folder / "data.log").string(), recordings::describe_timeline(log));
}

void report_replay(NodeContext& ctx, const recordings::DatadumperLog& log,
                   const recordings::ReplayCursor& cursor) {
  const recordings::DumpTimeline& t = log.timeline;
  ctx.report_metric("messages", log.entries.size());
  ctx.report_metric("delivered", cursor.delivered());
  ctx.report_metric("span_s", t.last_s - t.first_s);
  ctx.report_metric("median_rate_hz", t.median_step_s > 0.0 ? 1.0 / t.median_step_s : 0.0);
  nlohmann::json gaps = nlohmann::json::array();
  double longest = 0.0;
  for (const auto& g : t.gaps) {
    gaps.push_back({{"line", g.line}, {"from_s", g.from_s}, {"to_s", g.to_s}});
    longest = std::max(longest, g.to_s - g.from_s);
  }
  ctx.report_metric("gaps", gaps);
  ctx.report_metric("longest_gap_s", longest);
  nlohmann::json dropped = nlohmann::json::array();
  for (const auto& r : t.reversals)
    dropped.push_back({{"line", r.line},
                       {"stamp_s", r.stamp_s},
                       {"previous_line", r.previous_line},
                       {"previous_s", r.previous_s}});
  ctx.report_metric("dropped_lines", dropped);
}

}  // namespace somasim::plugins
