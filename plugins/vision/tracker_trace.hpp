#pragma once
// The object tracker's per-frame trace: one CSV row per stereo frame with each eye's track, the
// fix or the check that refused it, the filter's state, whether its velocity was reported, and
// the truth when it is wired. For reading why an object was seen late or wrongly; written whole
// at the end of the run.
#include <cstddef>
#include <filesystem>
#include <string>

#include "somasim/pps/ports.hpp"
#include "somasim/vision/stereo_object_tracker.hpp"

namespace somasim::plugins {

class TrackerTrace {
 public:
  TrackerTrace();
  /// The frame rendered at `time_s` [s]: its outcome `fix` (positions root frame [m], velocities
  /// [m/s], image positions [px]), whether the reported stimulus carried the velocity, and the
  /// truth (null: not wired).
  void add(double time_s, const vision::StereoFix& fix, bool velocity_reported,
           const pps::Stimulus* truth);
  std::size_t rows() const { return rows_; }
  /// Writes the table (header and every row) to `file`, whole or not at all.
  void write(const std::filesystem::path& file) const;

 private:
  std::string text_;
  std::size_t rows_ = 0;
};

}  // namespace somasim::plugins
