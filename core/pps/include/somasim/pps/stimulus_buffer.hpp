#pragma once
/// @file
/// Time-limited buffer of stimulus samples (root frame), pushed every ~50 ms.
#include <vector>

#include "somasim/pps/stimulus.hpp"

namespace somasim::pps {

/// One buffered sample: time [s] and the stimulus in the root frame.
struct StimulusSample {
  double time = 0.0;  ///< [s]
  Stimulus stimulus;
};

struct BufferSpec {
  /// Samples older than `horizon_s` before the newest one are dropped (a sample is kept while
  /// newest.time - time < horizon_s, so 4 s at 50 ms keeps 80 samples). <= 0: keep all.
  double horizon_s = 4.0;
  /// The whole buffer is forgotten when no stimulus arrived for more than this [s].
  double reset_after_s = 2.0;

  static BufferSpec paper() { return BufferSpec{3.0, 2.0}; }
  static BufferSpec code() { return BufferSpec{4.0, 2.0}; }
};

class StimulusBuffer {
 public:
  explicit StimulusBuffer(const BufferSpec& spec = {});

  /// Appends a sample (times must not decrease; an older sample clears the buffer first).
  /// If more than reset_after_s passed since the previous sample, the buffer is cleared first.
  void push(const StimulusSample& s);
  /// Tells the buffer the current time [s] when no stimulus is seen; forgets everything once
  /// more than reset_after_s passed since the last sample.
  void update(double now);
  void clear() { samples_.clear(); }

  const std::vector<StimulusSample>& samples() const { return samples_; }
  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  const BufferSpec& spec() const { return spec_; }

 private:
  BufferSpec spec_;
  std::vector<StimulusSample> samples_;
};

}  // namespace somasim::pps
