#include "somasim/vision/settling_gate.hpp"

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::vision {

namespace {
constexpr int kFewestFixesForARate = 3;  // a slope through two noisy radii is not a rate
}  // namespace

SettlingGate::SettlingGate(double max_radius_rate, int window_fixes)
    : max_radius_rate_(max_radius_rate), window_fixes_(window_fixes) {
  if (!(max_radius_rate > 0.0))
    throw InputError(
        fmt::format("a settling gate needs a radius rate > 0, got {}", max_radius_rate));
  if (window_fixes < 2)
    throw InputError(fmt::format("a settling gate reads at least 2 fixes, got {}", window_fixes));
}

bool SettlingGate::update(int window_fixes, double radius_rate) {
  if (window_fixes <= 1)
    fixes_since_unsettled_ = window_fixes_;  // a new track starts settled
  else if (window_fixes >= kFewestFixesForARate && radius_rate > max_radius_rate_)
    fixes_since_unsettled_ = 0;
  else
    ++fixes_since_unsettled_;
  return window_fixes >= window_fixes_ && fixes_since_unsettled_ >= window_fixes_;
}

}  // namespace somasim::vision
