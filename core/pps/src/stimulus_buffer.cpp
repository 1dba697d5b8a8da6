#include "somasim/pps/stimulus_buffer.hpp"

#include <algorithm>

namespace somasim::pps {

StimulusBuffer::StimulusBuffer(const BufferSpec& spec) : spec_(spec) {
  samples_.reserve(128);
}

void StimulusBuffer::push(const StimulusSample& s) {
  if (!samples_.empty()) {
    const double last = samples_.back().time;
    if (s.time < last || s.time - last > spec_.reset_after_s) samples_.clear();
  }
  samples_.push_back(s);
  if (spec_.horizon_s > 0.0) {
    const double newest = s.time;
    const auto first_kept = std::find_if(
        samples_.begin(), samples_.end(),
        [&](const StimulusSample& x) { return newest - x.time < spec_.horizon_s - 1e-9; });
    samples_.erase(samples_.begin(), first_kept);
  }
}

void StimulusBuffer::update(double now) {
  if (!samples_.empty() && now - samples_.back().time > spec_.reset_after_s) samples_.clear();
}

}  // namespace somasim::pps
