#include "somasim/recordings/replay_cursor.hpp"

#include "somasim/error.hpp"

namespace somasim::recordings {

ReplayCursor::ReplayCursor(const std::vector<DumpEntry>& entries, double offset_s)
    : entries_(&entries), origin_s_(0.0), offset_s_(offset_s) {
  if (entries.empty()) throw InputError("a replay needs at least one message");
  origin_s_ = entries.front().stamp_s;
}

std::span<const DumpEntry> ReplayCursor::advance_to(double sim_time_s) {
  const std::size_t first = next_;
  // A tolerance of a nanosecond keeps a message stamped exactly on a tick due at that tick.
  while (next_ < entries_->size() && due_time((*entries_)[next_]) <= sim_time_s + 1e-9) ++next_;
  return {entries_->data() + first, next_ - first};
}

}  // namespace somasim::recordings
