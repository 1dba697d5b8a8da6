#pragma once
// Reading one 8x4 count table from histograms_2D_long.csv and smoothing it into an activation
// landscape (Parzen windows at bin centres, sigma = one bin width per axis, max-normalised).
#include <string>
#include <vector>

namespace somasim::tools {

/// One stored (D, TTC) count table. Bins are D-major: index = d_bin * ttc_bins + ttc_bin.
struct CountTable {
  std::string source, part;
  int taxel = 0;
  int d_bins = 0, ttc_bins = 0;
  std::vector<double> d_edges;    ///< [m], d_bins + 1 values
  std::vector<double> ttc_edges;  ///< [s], ttc_bins + 1 values
  std::vector<double> pos, neg;   ///< counts per bin
};

/// Identifies a table inside the CSV; empty part / taxel < 0 = "the only one".
struct TableKey {
  std::string source;
  std::string part;
  int taxel = -1;
};

/// Reads the table `key` from the CSV at `path`. Throws somasim::InputError when the file is
/// missing or malformed, when nothing matches, or when several tables match (the message lists
/// them so that the user can add --part / --taxel).
CountTable read_table(const std::string& path, const TableKey& key);

/// Activation landscape on a d_samples x ttc_samples lattice covering the table's ranges
/// (both ends included). Returned row-major with rows along TTC (row 0 = lowest TTC) and
/// columns along D; max-normalised to 1 (all zeros when the table has no positive counts).
/// r = pos / (pos + neg) per bin (0 for empty bins);
/// f(D, TTC) = sum_ij r_ij exp(-((D - cD_j)^2 / sD^2 + (TTC - cT_i)^2 / sT^2) / 2).
std::vector<double> landscape(const CountTable& t, int d_samples, int ttc_samples);

}  // namespace somasim::tools
