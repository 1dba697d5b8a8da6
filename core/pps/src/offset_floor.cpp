#include "somasim/pps/offset_floor.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "somasim/error.hpp"

namespace somasim::pps {

std::optional<FloorEstimate> estimate_floor(const TaxelMap& map, const FloorOptions& opt) {
  if (!(opt.min_fraction > 0.0 && opt.min_fraction <= 1.0))
    throw InputError("floor offset estimator: min_fraction is " + std::to_string(opt.min_fraction) +
                     ", expected a value in (0, 1]");
  if (opt.plateau_bins < 1)
    throw InputError("floor offset estimator: plateau_bins is " + std::to_string(opt.plateau_bins) +
                     ", expected at least 1");
  const GridSpec& g = map.grid();
  const double w = g.d_width();
  std::vector<double> marginal(static_cast<std::size_t>(g.d_bins), 0.0);
  for (int i = 0; i < g.d_bins; ++i)
    for (int j = 0; j < g.ttc_bins; ++j)
      marginal[static_cast<std::size_t>(i)] += map.pos()[static_cast<std::size_t>(g.index(i, j))];
  const double largest = *std::max_element(marginal.begin(), marginal.end());
  if (largest <= 0.0) return std::nullopt;
  int lowest = 0;
  while (marginal[static_cast<std::size_t>(lowest)] < opt.min_fraction * largest) ++lowest;
  if (lowest + 1 >= g.d_bins) return std::nullopt;
  FloorEstimate e;
  int n = 0;
  for (int i = lowest + 1; i < g.d_bins && n < opt.plateau_bins; ++i, ++n)
    e.plateau += marginal[static_cast<std::size_t>(i)];
  e.plateau /= n;
  if (!(e.plateau >= opt.min_plateau_count) || e.plateau <= 0.0) return std::nullopt;
  e.edge_m = g.d_min + lowest * w;
  e.lowest_count = marginal[static_cast<std::size_t>(lowest)];
  e.below_count = lowest > 0 ? marginal[static_cast<std::size_t>(lowest - 1)] : 0.0;
  e.offset_m = e.edge_m + w * std::clamp(1.0 - e.lowest_count / e.plateau, 0.0, 1.0) -
               w * std::clamp(e.below_count / e.plateau, 0.0, 1.0);
  return e;
}

std::optional<double> estimate_offset_floor(const TaxelMap& map, const FloorOptions& opt) {
  const auto e = estimate_floor(map, opt);
  if (!e) return std::nullopt;
  return e->offset_m;
}

}  // namespace somasim::pps
