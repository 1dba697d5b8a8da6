#pragma once
// Reading one (D, TTC) count table from histograms_2D_long.csv.
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

}  // namespace somasim::tools
