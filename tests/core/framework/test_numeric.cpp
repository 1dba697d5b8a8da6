// to_integer: every finite double whose rounded value fits the integer type converts exactly,
// every other one (out of range, NaN, ±inf) gives no value — over generated doubles of every
// magnitude and the values next to each type's bounds; to_integer_clamped holds its bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "somasim/numeric.hpp"

using somasim::Rounding;
using somasim::to_integer;
using somasim::to_integer_clamped;

namespace {

// Doubles of every binary exponent and sign, the bounds of the common integer types and their
// neighbours, and the special values.
std::vector<double> generated_doubles() {
  std::vector<double> out{0.0,
                          -0.0,
                          0.5,
                          -0.5,
                          1.5,
                          -2.5,
                          std::nan(""),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::max(),
                          std::numeric_limits<double>::lowest(),
                          std::numeric_limits<double>::denorm_min()};
  for (const double bound : {127.0, 128.0, 255.0, 256.0, 2147483647.0, 2147483648.0, 4294967295.0,
                             4294967296.0, 9223372036854775807.0, 18446744073709551615.0})
    for (const double b : {bound, -bound, -bound - 1})
      for (const double x : {std::nextafter(b, -INFINITY), b, std::nextafter(b, INFINITY), b - 0.5,
                             b + 0.5, b - 0.4, b + 0.4})
        out.push_back(x);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> mantissa(0.5, 1.0);
  for (int e = -60; e <= 1030; ++e)
    for (int k = 0; k < 4; ++k) {
      const double x = std::ldexp(mantissa(rng), e);
      out.push_back(k % 2 ? -x : x);
    }
  return out;
}

double rounded(double x, Rounding mode) {
  switch (mode) {
    case Rounding::kNearest:
      return std::round(x);
    case Rounding::kDown:
      return std::floor(x);
    case Rounding::kUp:
      return std::ceil(x);
    case Rounding::kTowardZero:
      return std::trunc(x);
  }
  return x;
}

template <class I>
void check_type() {
  const long double lo = static_cast<long double>(std::numeric_limits<I>::lowest());
  const long double hi = static_cast<long double>(std::numeric_limits<I>::max());
  int converted = 0, refused = 0;
  for (const double x : generated_doubles())
    for (const Rounding mode :
         {Rounding::kNearest, Rounding::kDown, Rounding::kUp, Rounding::kTowardZero}) {
      const std::optional<I> v = to_integer<I>(x, mode);
      const long double r = static_cast<long double>(rounded(x, mode));
      const bool fits = std::isfinite(x) && r >= lo && r <= hi;
      ASSERT_EQ(v.has_value(), fits) << x;
      if (v) {
        EXPECT_EQ(static_cast<long double>(*v), r) << x;
        ++converted;
      } else {
        ++refused;
      }
    }
  EXPECT_GT(converted, 100);
  EXPECT_GT(refused, 100);
}

}  // namespace

TEST(Numeric, ToIntegerIsExactInRangeAndRefusesTheRest) {
  check_type<std::int8_t>();
  check_type<std::uint8_t>();
  check_type<int>();
  check_type<unsigned>();
  check_type<std::int64_t>();
  check_type<std::uint64_t>();
}

TEST(Numeric, ClampedHoldsItsBounds) {
  for (const double x : generated_doubles()) {
    const int v = to_integer_clamped<int>(x, -5, 1000);
    EXPECT_GE(v, -5) << x;
    EXPECT_LE(v, 1000) << x;
    if (std::isfinite(x) && x > -5 && x < 1000) {
      EXPECT_EQ(v, static_cast<int>(std::round(x)));
    }
  }
  EXPECT_EQ(to_integer_clamped<int>(std::nan(""), 3, 9), 3);
}
