#pragma once
/// @file
/// Conversions from floating point to integers that cannot overflow: a double outside the
/// target type's range (or NaN, ±inf) has no integer value, and converting it with
/// static_cast is undefined behaviour. These return std::nullopt instead, so that the caller
/// says what was out of range (a located error) rather than running with a wrapped count.
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>

namespace somasim {

/// How a double becomes an integer.
enum class Rounding : unsigned char { kNearest, kDown, kUp, kTowardZero };

/// `x` rounded by `mode` to an integer of type I, or std::nullopt when it is not finite or the
/// rounded value lies outside I's range.
template <std::integral I>
std::optional<I> to_integer(double x, Rounding mode = Rounding::kNearest) {
  if (!std::isfinite(x)) return std::nullopt;
  double r = x;
  switch (mode) {
    case Rounding::kNearest:
      r = std::round(x);
      break;
    case Rounding::kDown:
      r = std::floor(x);
      break;
    case Rounding::kUp:
      r = std::ceil(x);
      break;
    case Rounding::kTowardZero:
      r = std::trunc(x);
      break;
  }
  // The bounds as doubles: the lowest is a power of two (exact); the highest + 1 is one too.
  constexpr double lowest = static_cast<double>(std::numeric_limits<I>::lowest());
  // (max + 1 = 2^digits: digits excludes the sign bit.)
  const double above_max = std::ldexp(1.0, std::numeric_limits<I>::digits);
  if (r < lowest || r >= above_max) return std::nullopt;
  return static_cast<I>(r);
}

/// `x` rounded by `mode` and clamped to [lo, hi] (NaN gives lo): for counts that are bounded
/// by design (pixels on a canvas, samples along a path).
template <std::integral I>
I to_integer_clamped(double x, I lo, I hi, Rounding mode = Rounding::kNearest) {
  if (std::isnan(x)) return lo;
  if (x <= static_cast<double>(lo)) return lo;
  if (x >= static_cast<double>(hi)) return hi;
  return to_integer<I>(x, mode).value_or(lo);
}

}  // namespace somasim
