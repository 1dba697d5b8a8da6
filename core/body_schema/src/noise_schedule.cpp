#include "somasim/body_schema/noise_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "somasim/error.hpp"

namespace somasim::body_schema {

double NoiseSchedule::next_sigma(double sigma_deg, bool resampled) const {
  const double next = sigma_deg * (resampled ? factor_after_resample : factor_without_resample);
  return std::clamp(next, min_sigma_deg, max_sigma_deg);
}

const std::vector<std::string>& noise_schedule_names() {
  static const std::vector<std::string> names = {"paper", "code2016", "code2017"};
  return names;
}

NoiseSchedule noise_schedule_preset(std::string_view name) {
  NoiseSchedule s;
  if (name == "paper") return s;
  if (name == "code2016" || name == "code2017") {
    s.initial_sigma_deg = 3.5;
    s.step_sigma_deg = 3.0;
    s.factor_after_resample = 0.85;
    s.factor_without_resample = name == "code2016" ? 1.15 : 1.2;
    s.min_sigma_deg = 0.04;
    s.max_sigma_deg = 3.5;
    s.resample_threshold = 0.55;
    s.reset_particle_zero = name == "code2017";
    return s;
  }
  throw InputError(
      fmt::format("unknown noise schedule '{}' (expected paper, code2016 or code2017)", name));
}

}  // namespace somasim::body_schema
