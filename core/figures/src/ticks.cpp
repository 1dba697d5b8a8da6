// Nice tick positions and their labels.
#include "somasim/figures/ticks.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "somasim/error.hpp"

namespace somasim::figures {
namespace {

void check(double lo, double hi, int max_ticks) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    std::ostringstream os;
    os << "nice_ticks: range [" << lo << ", " << hi << "] is invalid; expected finite lo < hi";
    throw InputError(os.str());
  }
  if (max_ticks < 2)
    throw InputError("nice_ticks: max_ticks is " + std::to_string(max_ticks) +
                     "; expected at least 2");
}

long long first_k(double lo, double step) {
  return static_cast<long long>(std::ceil(lo / step - 1e-9));
}
long long last_k(double hi, double step) {
  return static_cast<long long>(std::floor(hi / step + 1e-9));
}

}  // namespace

double nice_step(double lo, double hi, int max_ticks) {
  check(lo, hi, max_ticks);
  const double span = hi - lo;
  double mag = std::pow(10.0, std::floor(std::log10(span / max_ticks)));
  // Walk up 1, 2, 5, 10, 20, ... x mag until the count fits.
  static constexpr double kMult[] = {1, 2, 5};
  for (int decade = 0; decade < 4; ++decade, mag *= 10) {
    for (double m : kMult) {
      const double step = m * mag;
      if (last_k(hi, step) - first_k(lo, step) + 1 <= max_ticks) return step;
    }
  }
  return mag;  // unreachable in practice
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  const double step = nice_step(lo, hi, max_ticks);
  std::vector<double> out;
  for (long long k = first_k(lo, step); k <= last_k(hi, step); ++k) {
    double v = static_cast<double>(k) * step;
    if (k == 0) v = 0.0;
    out.push_back(v);
  }
  return out;
}

std::string format_tick(double v, double step) {
  int decimals = 0;
  step = std::fabs(step);
  if (step > 0 && std::isfinite(step)) {
    while (decimals < 12) {
      const double scaled = step * std::pow(10.0, decimals);
      if (std::fabs(scaled - std::round(scaled)) < 1e-6 * std::max(1.0, scaled)) break;
      ++decimals;
    }
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  // "-0", "-0.00" -> "0", "0.00"
  if (s[0] == '-' && s.find_first_not_of("0.", 1) == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace somasim::figures
