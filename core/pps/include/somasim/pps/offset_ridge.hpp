#pragma once
/// @file
/// Systematic offset from where the positive ridge ends ("ridge-end" estimator).
///
/// Why not Fig 8: the activation-weighted regression of [D, TTC] fits the whole approach band,
/// which (signed TTC) runs through the origin whatever the offset, or (unsigned TTC, samples
/// kept behind the skin) folds into a V around D = 0; its D at TTC = 0 follows the band's
/// slope, not its end.
///
/// Idea: the positive counts of a taxel come from approaches that ended in contact with it.
/// Sampled at a fixed rate dt, an approach of speed s leaves one sample per s*dt metres of
/// path; far from the taxel the path is radial, so D drops by s*dt per sample. Counting
/// positive samples below a reference distance D_ref (above every contact point) therefore
/// measures the path length from D_ref to the contact, in units of what one "plateau" bin
/// [D_ref, D_ref + w) receives per w metres:
///
///   offset = D_ref - w * (positive counts with D < D_ref) / (positive counts in the plateau)
///
/// summed over all TTC bins (the D-marginal of the positive counts). This is the mean, over
/// touching approaches (weights 1/s), of D_ref minus the path length: the contact's distance
/// along the normal (-|o| + l^2 / (2 D_ref) for an approach along the normal with lateral miss
/// l). Samples bunching near the skin (slow radial motion close to the taxel, the jump from
/// +|p| to -|p| when the perceived path crosses the skin plane) do not bias it: only their
/// number counts, not where in D they fall. Sub-bin resolution comes from the counts.
///
/// Valid when: every touching approach passes D_ref + w radially and all its samples below
/// D_ref + w are in the map (TTC within range: (D_ref + w) / speed <= ttc_max for the unsigned
/// TTC); samples behind the skin are counted (a receptive field mirrored below the skin, and
/// for negative offsets the unsigned TTC: with the signed TTC the perceived path past its
/// closest point to the taxel is receding and dropped, so a negative offset leaves no trace in
/// the map - the estimate then reads about 0); the offset lies in [d_min, D_ref).
#include <cstdint>
#include <optional>

#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

struct RidgeEndOptions {
  /// D_ref [m] is the first D bin edge at or above this value (strictly above d_min).
  double ref_min_m = 0.04;
  /// Bins above D_ref averaged for the plateau count (>= 1; fewer if the grid ends).
  int plateau_bins = 1;
  /// Fewer positive counts per plateau bin than this: no estimate.
  double min_plateau_count = 5.0;
};

struct RidgeEndEstimate {
  double offset_m = 0.0;      ///< estimated D at contact [m]
  double ref_m = 0.0;         ///< D_ref [m]
  double plateau = 0.0;       ///< mean positive counts per plateau bin
  double counts_below = 0.0;  ///< positive counts with D < D_ref
};

/// The ridge-end estimate with its ingredients; nullopt when the grid has no bin edge at or
/// above ref_min_m with a bin above it, or the plateau has too few counts. Uses counts only
/// (works for any number of TTC bins, the distance-only map included).
std::optional<RidgeEndEstimate> estimate_ridge_end(const TaxelMap& map,
                                                   const RidgeEndOptions& opt = {});

/// Just the offset [m] of estimate_ridge_end().
std::optional<double> estimate_offset_ridge(const TaxelMap& map, const RidgeEndOptions& opt = {});

}  // namespace somasim::pps
