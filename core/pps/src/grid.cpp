#include "somasim/pps/grid.hpp"

#include "somasim/config.hpp"

#include <cmath>
#include <sstream>

namespace somasim::pps {

bool GridSpec::bin_of(double d, double ttc, int& d_bin, int& ttc_bin) const {
  if (!(d >= d_min && d <= d_max && ttc >= ttc_min && ttc <= ttc_max)) return false;
  d_bin = static_cast<int>((d - d_min) / d_width());
  ttc_bin = static_cast<int>((ttc - ttc_min) / ttc_width());
  if (d_bin >= d_bins) d_bin = d_bins - 1;
  if (ttc_bin >= ttc_bins) ttc_bin = ttc_bins - 1;
  return true;
}

std::string GridSpec::validate() const {
  std::ostringstream os;
  if (!(std::isfinite(d_min) && std::isfinite(d_max) && d_min < d_max))
    os << "D range [" << d_min << ", " << d_max << "] m must be finite with d_min < d_max";
  else if (!(std::isfinite(ttc_min) && std::isfinite(ttc_max) && ttc_min < ttc_max))
    os << "TTC range [" << ttc_min << ", " << ttc_max
       << "] s must be finite with ttc_min < ttc_max";
  else if (d_bins < 1 || d_bins > kMaxBinsPerAxis)
    os << "d_bins = " << d_bins << " must be in [1, " << kMaxBinsPerAxis << "]";
  else if (ttc_bins < 1 || ttc_bins > kMaxBinsPerAxis)
    os << "ttc_bins = " << ttc_bins << " must be in [1, " << kMaxBinsPerAxis << "]";
  return os.str();
}

void GridSpec::validate(ConfigChecks& checks) const {
  checks.require(d_max > d_min, d_max,
                 "must be greater than d_min (" + std::to_string(d_min) + ")");
}

std::string ParzenSpec::validate() const {
  if (!(std::isfinite(sigma_scale) && sigma_scale > 0.0)) {
    std::ostringstream os;
    os << "sigma_scale = " << sigma_scale << " must be a positive number";
    return os.str();
  }
  return {};
}

const char* to_string(KernelAnchor a) {
  return enum_name(a).data();
}

bool parse_kernel_anchor(const std::string& s, KernelAnchor& out) {
  const auto parsed = parse_enum<KernelAnchor>(s);
  if (parsed) out = *parsed;
  return parsed.has_value();
}

const char* to_string(PpsModel m) {
  return enum_name(m).data();
}

bool parse_pps_model(const std::string& s, PpsModel& out) {
  const auto parsed = parse_enum<PpsModel>(s);
  if (parsed) out = *parsed;
  return parsed.has_value();
}

GridSpec distance_only_grid(const GridSpec& g) {
  return GridSpec{g.d_min, g.d_max, g.d_bins, 0.0, 1.0, 1};
}

double distance_only_query_ttc(const GridSpec& g, const ParzenSpec& p) {
  return g.ttc_min + (p.anchor == KernelAnchor::kCentre ? 0.5 : 0.0) * g.ttc_width();
}

}  // namespace somasim::pps
