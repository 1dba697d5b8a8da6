#pragma once
// Sample statistics shared by the body-schema reports: mean and standard deviation (n − 1), and
// the median. Empty samples give NaN.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace somasim::plugins {

struct MeanSd {
  double mean = NAN, sd = NAN;  ///< sd is 0 for a single value
  int n = 0;
};

inline MeanSd mean_sd(const std::vector<double>& v) {
  MeanSd s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0.0;
  return s;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace somasim::plugins
