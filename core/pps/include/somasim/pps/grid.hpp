#pragma once
/// @file
/// The (D, TTC) grid of a PPS taxel map and the Parzen smoothing variant.
///
/// D is the signed distance [m] of a stimulus from the taxel (negative behind the skin plane),
/// TTC its time to contact [s]. Both ranges are closed intervals; the grid has `d_bins` x
/// `ttc_bins` equal bins, stored D-major: index = d_bin * ttc_bins + ttc_bin.
#include <cstddef>
#include <span>
#include <string>

#include "somasim/name_table.hpp"

namespace somasim {
class ConfigChecks;  // somasim/config.hpp
}  // namespace somasim

namespace somasim::pps {

/// Largest number of bins per axis supported (keeps queries allocation-free).
inline constexpr int kMaxBinsPerAxis = 32;

/// Grid over D [m] x TTC [s]. Defaults: the paper text's (TTC up to 3 s; the released robot
/// code's 1.2 s is code()).
struct GridSpec {
  double d_min = -0.10;  ///< [m] lower edge of the first D bin.
  double d_max = 0.20;   ///< [m] upper edge of the last D bin.
  int d_bins = 8;        ///< number of D bins.
  double ttc_min = 0.0;  ///< [s] lower edge of the first TTC bin.
  double ttc_max = 3.0;  ///< [s] upper edge of the last TTC bin (released code: 1.2 s).
  int ttc_bins = 4;      ///< number of TTC bins.

  double d_width() const { return (d_max - d_min) / d_bins; }          ///< [m]
  double ttc_width() const { return (ttc_max - ttc_min) / ttc_bins; }  ///< [s]
  std::size_t size() const { return static_cast<std::size_t>(d_bins) * ttc_bins; }
  /// Index of bin (d_bin, ttc_bin) in the D-major layout.
  int index(int d_bin, int ttc_bin) const { return d_bin * ttc_bins + ttc_bin; }

  /// True when (d, ttc) lies in the closed ranges; then writes the bin indices (a value on the
  /// upper edge goes to the last bin).
  bool bin_of(double d, double ttc, int& d_bin, int& ttc_bin) const;

  /// Empty string when valid, else a description of what is wrong.
  std::string validate() const;

  /// The grid as a config block (somasim/config.hpp): d_min, d_max, d_bins, ttc_max, ttc_bins
  /// (TTC starts at ttc_min, not a parameter). Cross-field check: d_max > d_min.
  template <class V>
  void visit(V& v) {
    v.field("d_min", d_min).unit("m").range(-1, 1).doc("lower edge of the D range");
    v.field("d_max", d_max).unit("m").range(-1, 1).doc("upper edge of the D range");
    v.field("d_bins", d_bins).range(1, kMaxBinsPerAxis).doc("number of D bins");
    v.field("ttc_max", ttc_max)
        .unit("s")
        .range(0.01, 100)
        .doc("upper edge of the TTC range (paper text 3 s; released robot code 1.2 s)");
    v.field("ttc_bins", ttc_bins).range(1, kMaxBinsPerAxis).doc("number of TTC bins");
  }
  void validate(ConfigChecks& checks) const;

  /// Paper text variant: TTC in [0, 3] s.
  static GridSpec paper() { return GridSpec{}; }
  /// Released robot code variant: TTC in [0, 1.2] s.
  static GridSpec code() { return GridSpec{-0.10, 0.20, 8, 0.0, 1.2, 4}; }

  bool operator==(const GridSpec&) const = default;
};

/// Where the Parzen kernels sit on each bin.
enum class KernelAnchor {
  kCentre,     ///< bin centres (paper; default).
  kLowerEdge,  ///< bin lower edges (released code: shifts the surface by half a bin).
};
inline constexpr NamedValue<KernelAnchor> kKernelAnchorNames[] = {
    {KernelAnchor::kCentre, "centre"}, {KernelAnchor::kLowerEdge, "lower_edge"}};
/// "centre", "lower_edge".
constexpr std::span<const NamedValue<KernelAnchor>> name_table(KernelAnchor) {
  return kKernelAnchorNames;
}

/// Parzen-window smoothing: sigma = sigma_scale x bin width, per axis.
struct ParzenSpec {
  double sigma_scale = 1.0;  ///< 1.0 (paper) or 0.75 (released code).
  KernelAnchor anchor = KernelAnchor::kCentre;

  static ParzenSpec paper() { return ParzenSpec{1.0, KernelAnchor::kCentre}; }
  static ParzenSpec code() { return ParzenSpec{0.75, KernelAnchor::kLowerEdge}; }

  std::string validate() const;  ///< Empty when valid.
  bool operator==(const ParzenSpec&) const = default;
};

/// Which representation a taxel learns.
enum class PpsModel {
  kDTtc,          ///< (D, TTC) map (paper).
  kDistanceOnly,  ///< D only (the paper's S2 ablation): TTC ignored in learning and queries.
};
inline constexpr NamedValue<PpsModel> kPpsModelNames[] = {
    {PpsModel::kDTtc, "d_ttc"}, {PpsModel::kDistanceOnly, "distance_only"}};
/// "d_ttc", "distance_only".
constexpr std::span<const NamedValue<PpsModel>> name_table(PpsModel) {
  return kPpsModelNames;
}

/// "d_ttc" / "distance_only".
const char* to_string(PpsModel m);
/// Parses "d_ttc" / "distance_only"; returns false on anything else.
bool parse_pps_model(const std::string& s, PpsModel& out);

/// The grid of a distance-only map: `g`'s D axis and one placeholder TTC bin [0, 1]. With one
/// TTC bin the Parzen sum queried at that bin's kernel anchor (distance_only_query_ttc) is the
/// 1-D Parzen sum over D, and the normaliser its maximum over the D anchors.
GridSpec distance_only_grid(const GridSpec& g);
/// The TTC at which a distance-only map (grid from distance_only_grid) is queried.
double distance_only_query_ttc(const GridSpec& g, const ParzenSpec& p);

/// "centre" / "lower_edge".
const char* to_string(KernelAnchor a);
/// Parses "centre" / "lower_edge"; returns false on anything else.
bool parse_kernel_anchor(const std::string& s, KernelAnchor& out);

}  // namespace somasim::pps
