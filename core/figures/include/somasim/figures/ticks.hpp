#pragma once
/// @file
/// "Nice" axis ticks: multiples of 1, 2 or 5 x 10^k.
#include <string>
#include <vector>

namespace somasim::figures {

/// Tick positions inside the closed range [lo, hi]: multiples of the smallest step in
/// {1, 2, 5} x 10^k that yields at most `max_ticks` ticks (at least 2 unless the range is tiny).
/// Values are exact multiples (k * step, with -0 written as 0). Throws somasim::InputError when
/// lo or hi is not finite, lo >= hi, or max_ticks < 2.
std::vector<double> nice_ticks(double lo, double hi, int max_ticks = 8);

/// The step used by nice_ticks(lo, hi, max_ticks).
double nice_step(double lo, double hi, int max_ticks = 8);

/// Text of tick value `v` on an axis with tick spacing `step`: just enough decimals to tell
/// neighbouring ticks apart ("0.25", "1.5", "-10", never "-0").
std::string format_tick(double v, double step);

}  // namespace somasim::figures
