#pragma once
/// @file
/// Systematic offset from where the positive D-marginal ends ("floor" estimator): the perceived
/// D [m] of the stimulus at contact, D = sign(p_z)|p| (radial, as in stimulus.hpp).
///
/// Why a third estimator: the ridge end (offset_ridge.hpp) turns the positive counts below a
/// reference distance into a path length, i.e. it measures the contact's distance ALONG THE
/// NORMAL. A rigid kinematic error also shifts a taxel sideways (on the curved forearm by 1-2
/// cm): an approach that ends a lateral distance l beside the believed taxel, on its tangent
/// plane, has perceived D at contact = l, but its samples bunch near D = l (D = sqrt(l^2 + z^2)
/// barely changes in the last centimetres of a path along the normal) and their number still
/// equals the path length: the ridge end reads l^2 / (2 D_ref), about 0. Here the END of the
/// marginal is located instead, in D.
///
/// Method, on the positive counts summed over the TTC bins (the D-marginal M_i of bins
/// [e_i, e_i + w), w = bin width):
/// - the lowest "solid" bin i: M_i >= min_fraction x max_k M_k (stray samples below the ridge,
///   e.g. an approach that crossed the skin plane beside the taxel, are ignored);
/// - the plateau P: mean of M over the `plateau_bins` bins just above i (fewer where the grid
///   ends);
/// - floor = e_i + w * clamp(1 - M_i / P, 0, 1) - w * clamp(M_{i-1} / P, 0, 1).
/// Radial approaches (along the normal, counts proportional to path length): M_i / P is the
/// share of bin i the paths cover, so the floor is exact, the ridge-end result computed from the
/// bins next to the end (the last term adds the sliver of a path ending just below e_i; for a
/// mix of ends it gives their mean like the ridge end). Laterally offset approaches (samples
/// bunch near D = l, so M_i >= P): floor = e_i (minus the few counts of bin i-1), with l in
/// [e_i, e_i + w): error < w. Mixed ends (a spread of contact points): the estimate follows the
/// lower ones (those of at least min_fraction of the largest bin's counts), not the mean.
///
/// Resolution: one D bin width w in general (sub-bin for radial approaches), so a target of
/// 1 cm needs bins of at most 1 cm (e.g. 30 bins over [-0.1, 0.2] m), not the paper's 3.75 cm.
/// Valid when: the touching approaches leave counts down to their contact (unsigned TTC and the
/// mirrored receptive field for contacts behind the skin plane, D >= d_min, TTC within range
/// for the plateau bins); the contact lies above the grid's lowest bin (else the ridge runs off
/// the grid and the floor reads a value near d_min); at least one bin above the solid one.
/// Uses counts only (works for any number of TTC bins, the distance-only map included).
#include <optional>

#include "somasim/pps/taxel_map.hpp"

namespace somasim::pps {

struct FloorOptions {
  /// A bin is solid when its positive count is at least this share of the largest bin's, in
  /// (0, 1].
  double min_fraction = 0.4;
  /// Bins above the lowest solid one averaged for the plateau count (>= 1).
  int plateau_bins = 3;
  /// Fewer positive counts per plateau bin than this: no estimate (a touching approach at
  /// 5-15 cm/s sampled at 20 Hz leaves 1-4 counts per 1 cm bin).
  double min_plateau_count = 2.0;
};

struct FloorEstimate {
  double offset_m = 0.0;      ///< estimated perceived D at contact [m]
  double edge_m = 0.0;        ///< lower edge e_i of the lowest solid bin [m]
  double plateau = 0.0;       ///< P, mean positive counts per plateau bin
  double lowest_count = 0.0;  ///< M_i, positive counts of the lowest solid bin
  double below_count = 0.0;   ///< M_{i-1}, positive counts of the bin below it (0 at d_min)
};

/// The floor estimate with its ingredients; nullopt when the map has no positive count, the
/// lowest solid bin is the grid's last, or the plateau has fewer than min_plateau_count counts.
/// InputError for min_fraction outside (0, 1] or plateau_bins < 1 (message names the option).
std::optional<FloorEstimate> estimate_floor(const TaxelMap& map, const FloorOptions& opt = {});

/// Just the offset [m] of estimate_floor().
std::optional<double> estimate_offset_floor(const TaxelMap& map, const FloorOptions& opt = {});

}  // namespace somasim::pps
