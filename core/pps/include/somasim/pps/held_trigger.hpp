#pragma once
/// @file
/// A threshold crossing that counts once it has held: the trigger of the PPS controllers and of
/// their evaluation, so that a transient of the perceived stimulus as short as one camera frame
/// moves nothing, while a crossing far above the threshold (an object seen late and close) need
/// not wait. Times [s].
#include <limits>

namespace somasim::pps {

class HeldTrigger {
 public:
  /// `hold_s` >= 0: how long the activation must stay above the threshold; 0 = at once.
  explicit HeldTrigger(double hold_s = 0.0);

  /// Forget the current crossing (a new presentation).
  void reset() { above_since_s_ = kNever; }
  /// Whether the activation is `above` the threshold at `time_s` (non-decreasing across calls),
  /// and whether it is `sure` (above the level that needs no hold; implies above); returns
  /// whether the trigger holds now: above, and either sure or above without a break for at
  /// least hold_s (to 1 ns).
  bool update(double time_s, bool above, bool sure = false);
  double hold_s() const { return hold_s_; }

 private:
  static constexpr double kNever = std::numeric_limits<double>::quiet_NaN();
  double hold_s_;
  double above_since_s_ = kNever;  // start of the current crossing; NaN below the threshold
};

}  // namespace somasim::pps
