#pragma once
/// @file
/// The PPS "landscape" figure: a taxel map's activation over D [cm] (x) × TTC [s] (y), with the
/// bin grid and, optionally, the Fig 8 regression line and its D at TTC = 0, the floor estimate
/// of the offset (somasim/pps/offset_floor.hpp) and a known true offset as vertical lines. Used by
/// the pps_learner plugin and by tools that draw other maps (e.g. the authors' stored tables) the
/// same way. Library somasim_pps_plots (depends on somasim_pps and somasim_figures).
#include <optional>
#include <string>

#include "somasim/figures/heatmap.hpp"
#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

struct LandscapeOptions {
  std::string title;
  bool regression_line = true;          ///< overlay the activation-weighted orthogonal regression
  bool floor_line = true;               ///< vertical line at the floor estimate of the offset
  std::optional<double> true_offset_m;  ///< vertical line at the offset the taxel should show [m]
  bool bin_grid = true;                 ///< draw the D/TTC bin edges
  int d_samples = 301;                  ///< activation samples along D (both ends included)
  int ttc_samples = 121;                ///< ... along TTC
};

/// The heatmap spec of `map` (must not be stale); render it with figures::render_heatmap.
figures::HeatmapSpec landscape_heatmap(const TaxelMap& map, const LandscapeOptions& options);

}  // namespace somasim::pps
