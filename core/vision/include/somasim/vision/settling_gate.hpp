#pragma once
/// @file
/// Whether a track has settled onto one rigid object, read from how fast its radius changes: a
/// rigid object keeps its size, so a radius that grows or shrinks is a window still settling
/// onto its object or two eyes whose windows hold different things. The motion such fixes show
/// is the windows', and a filter fed with them remembers it: the track counts as settled only
/// once a whole window of fixes has come after the last unsettled one.
///
/// Rates in [1/s] (FixWindow::radius_rate: the radius' least-squares slope over its mean).

namespace somasim::vision {

class SettlingGate {
 public:
  /// `max_radius_rate` > 0 [1/s]: faster is unsettled; `window_fixes` >= 2: the fixes a rate is
  /// read over and the settled fixes that must follow an unsettled one. Throws
  /// somasim::InputError otherwise.
  SettlingGate(double max_radius_rate, int window_fixes);

  /// One fix of the track: `window_fixes` its window holds now (1: the first fix of a new track),
  /// `radius_rate` [1/s] over them. Returns whether the track is settled at this fix: its window
  /// full, and at least window_fixes fixes since the last whose rate (over three fixes or more)
  /// exceeded max_radius_rate; that fix and the window_fixes - 1 after it are not.
  bool update(int window_fixes, double radius_rate);

 private:
  double max_radius_rate_;
  int window_fixes_;
  int fixes_since_unsettled_ = 0;
};

}  // namespace somasim::vision
