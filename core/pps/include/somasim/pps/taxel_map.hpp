#pragma once
/// @file
/// Per-taxel PPS map: positive/negative counts on the (D, TTC) grid and the Parzen activation.
#include <array>
#include <cstdint>
#include <vector>

#include "somasim/pps/grid.hpp"

namespace somasim::pps {

/// Counts of one taxel and its smoothed activation.
///
/// Activation (exactly the released code's normalisation):
///   f(D, TTC) = sum_ij r_ij exp(-((D - a_i)^2 / (2 sD^2) + (TTC - b_j)^2 / (2 sT^2)))
/// with r_ij = pos/(pos+neg) (0 for an empty bin), kernel anchors a_i, b_j (bin centres or lower
/// edges) and sD, sT = sigma_scale x bin width. activation = f / M, where M is the maximum of f
/// over the d_bins x ttc_bins kernel anchor points (a_i, b_j) - not over the continuum - clamped
/// to [0, 1]; 0 outside the closed D/TTC ranges or when M = 0. M is cached and refreshed when
/// counts change. Queries are separable (f = g(D)^T R h(TTC)), use 4 exp() calls and do not
/// allocate.
class TaxelMap {
 public:
  using Count = std::uint32_t;

  TaxelMap(const GridSpec& grid, const ParzenSpec& parzen);
  /// From counts in D-major order (size grid.size() each). SOMASIM_CHECKs the sizes.
  TaxelMap(const GridSpec& grid, const ParzenSpec& parzen, std::vector<Count> pos,
           std::vector<Count> neg);

  const GridSpec& grid() const { return grid_; }
  const ParzenSpec& parzen() const { return parzen_; }

  /// Adds one sample at (d [m], ttc [s]) to the positive or negative counts. Returns false (and
  /// counts nothing) when outside the closed ranges. With refresh = false the cached normaliser
  /// goes stale until refresh() is called (for batches).
  bool add_sample(double d, double ttc, bool positive, bool refresh = true);
  /// Adds to the counts of bin `index` (D-major) without refreshing the normaliser.
  void add_to_bin(int index, bool positive) {
    (positive ? pos_ : neg_)[static_cast<std::size_t>(index)] += 1;
    stale_ = true;
  }
  /// Recomputes the ratios and the normaliser after add_to_bin / add_sample(..., false).
  void refresh();
  bool stale() const { return stale_; }

  const std::vector<Count>& pos() const { return pos_; }
  const std::vector<Count>& neg() const { return neg_; }
  /// r = pos / (pos + neg), 0 for an empty bin.
  double ratio(int d_bin, int ttc_bin) const;

  /// Unnormalised Parzen sum f(d, ttc) (defined everywhere).
  double parzen(double d, double ttc) const;
  /// Normalised activation in [0, 1]; 0 outside the grid ranges. Requires !stale().
  double activation(double d, double ttc) const;
  /// The cached normaliser M (0 when all ratios are 0).
  double normaliser() const { return norm_; }

  /// Reference implementation: one 2-D Gaussian per bin (32 exp()), cached normaliser (for
  /// tests and benchmarks).
  double activation_naive(double d, double ttc) const;

 private:
  void kernel_d(double d, double* g) const;
  void kernel_t(double t, double* h) const;

  GridSpec grid_;
  ParzenSpec parzen_;
  std::vector<Count> pos_, neg_;
  std::vector<double> ratio_;  // D-major
  double a0_, b0_;             // first anchors [m], [s]
  double inv_sd_, inv_st_;     // 1 / (sigma * sqrt(2)) in units of the bin width
  double qd_, qt_;             // exp(-1 / s^2), s = sigma in bin widths
  double norm_ = 0.0, inv_norm_ = 0.0;
  bool stale_ = false;
};

}  // namespace somasim::pps
