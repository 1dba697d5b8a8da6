#pragma once
/// @file
/// Systematic offset of a learned map (Roncone et al. 2016, Fig 8): weighted orthogonal (total
/// least squares) regression of [D, TTC] weighted by activation; the offset is the D [m] where
/// the fitted line meets TTC = 0.
#include <optional>

#include <Eigen/Core>

#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

struct OffsetOptions {
  /// The activation is evaluated on an n_d x n_ttc grid of points spanning the closed ranges
  /// [d_min, d_max] x [ttc_min, ttc_max] uniformly (end points included).
  int n_d = 61;
  int n_ttc = 61;
  /// Points with activation below this are left out (0: all points, weight = activation).
  double min_activation = 0.0;
};

/// The fitted line in map units: through `centre` (D [m], TTC [s]) along the unit `direction`.
struct RegressionLine {
  Eigen::Vector2d centre;
  Eigen::Vector2d direction;
};

/// The line of estimate_offset() (same fit, mapped back to D [m] x TTC [s]); nullopt when there
/// is no weight or no principal direction.
std::optional<RegressionLine> fit_activation_line(const TaxelMap& map,
                                                  const OffsetOptions& opt = {});

/// Fit, in scaled axes x = (D - d_min)/(d_max - d_min), y = (TTC - ttc_min)/(ttc_max - ttc_min)
/// (so that metres and seconds weigh alike), the line through the weighted mean along the
/// principal eigenvector of the weighted 2x2 covariance, and return its D at TTC = 0 [m].
/// nullopt when undefined: no weight, an isotropic spread (no principal direction), or a line
/// parallel to the D axis. The map must not be stale.
std::optional<double> estimate_offset(const TaxelMap& map, const OffsetOptions& opt = {});

}  // namespace somasim::pps
