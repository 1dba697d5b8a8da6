#include "somasim/pps/offset_ridge.hpp"

#include <cmath>
#include <vector>

namespace somasim::pps {

std::optional<RidgeEndEstimate> estimate_ridge_end(const TaxelMap& map,
                                                   const RidgeEndOptions& opt) {
  const GridSpec& g = map.grid();
  const double w = g.d_width();
  // First edge index k (edge = d_min + k w, 1 <= k < d_bins) at or above ref_min_m.
  int k = static_cast<int>(std::ceil((opt.ref_min_m - g.d_min) / w - 1e-9));
  if (k < 1) k = 1;
  if (k >= g.d_bins) return std::nullopt;
  std::vector<double> marginal(static_cast<std::size_t>(g.d_bins), 0.0);
  for (int i = 0; i < g.d_bins; ++i)
    for (int j = 0; j < g.ttc_bins; ++j)
      marginal[static_cast<std::size_t>(i)] += map.pos()[static_cast<std::size_t>(g.index(i, j))];
  RidgeEndEstimate e;
  e.ref_m = g.d_min + k * w;
  int n = 0;
  for (int i = k; i < g.d_bins && n < std::max(1, opt.plateau_bins); ++i, ++n)
    e.plateau += marginal[static_cast<std::size_t>(i)];
  e.plateau /= n;
  if (!(e.plateau >= opt.min_plateau_count) || e.plateau <= 0.0) return std::nullopt;
  for (int i = 0; i < k; ++i) e.counts_below += marginal[static_cast<std::size_t>(i)];
  e.offset_m = e.ref_m - w * e.counts_below / e.plateau;
  return e;
}

std::optional<double> estimate_offset_ridge(const TaxelMap& map, const RidgeEndOptions& opt) {
  const auto e = estimate_ridge_end(map, opt);
  if (!e) return std::nullopt;
  return e->offset_m;
}

}  // namespace somasim::pps
