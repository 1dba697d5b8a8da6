#pragma once
/// @file
/// Walks a log's messages along the simulated clock: a message stamped `stamp` [s] is due at
/// simulated time `stamp - first stamp + offset_s` (the first message at `offset_s`).
#include <cstddef>
#include <span>
#include <vector>

#include "somasim/recordings/datadumper_log.hpp"

namespace somasim::recordings {

class ReplayCursor {
 public:
  /// `entries` (non-decreasing stamps, as read_datadumper_log gives them) must outlive the
  /// cursor and not be empty.
  ReplayCursor(const std::vector<DumpEntry>& entries, double offset_s);

  /// Simulated time [s] at which `entry` is due.
  double due_time(const DumpEntry& entry) const { return entry.stamp_s - origin_s_ + offset_s_; }
  /// The messages due at or before `sim_time_s` that earlier calls have not returned, in order.
  std::span<const DumpEntry> advance_to(double sim_time_s);
  /// True when every message has been returned.
  bool done() const { return next_ >= entries_->size(); }
  /// How many messages have been returned.
  std::size_t delivered() const { return next_; }
  /// Simulated time [s] of the last message.
  double end_time() const { return due_time(entries_->back()); }

 private:
  const std::vector<DumpEntry>* entries_;
  double origin_s_, offset_s_;
  std::size_t next_ = 0;
};

}  // namespace somasim::recordings
