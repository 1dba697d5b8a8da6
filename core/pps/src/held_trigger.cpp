#include "somasim/pps/held_trigger.hpp"

#include <cmath>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::pps {

namespace {
constexpr double kTimeEps = 1e-9;  // [s]
}  // namespace

HeldTrigger::HeldTrigger(double hold_s) : hold_s_(hold_s) {
  if (!(hold_s >= 0.0) || !std::isfinite(hold_s))
    throw InputError(
        fmt::format("a trigger's hold time must be finite and >= 0 s, got {}", hold_s));
}

bool HeldTrigger::update(double time_s, bool above, bool sure) {
  if (!above) {
    above_since_s_ = kNever;
    return false;
  }
  if (std::isnan(above_since_s_)) above_since_s_ = time_s;
  return sure || time_s - above_since_s_ >= hold_s_ - kTimeEps;
}

}  // namespace somasim::pps
