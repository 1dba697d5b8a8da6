#pragma once
/// @file
/// Export of learned (D, TTC) maps in the original iCub peripersonalSpace `taxels2D_*.ini` format
/// (what ini_import.hpp reads): per body part a section `[part]` with `modality 2D`, `nTaxels`,
/// `ext (dmin dmax tmin tmax)`, `binsNum (nd nt)`, then `ID (positive counts) (negative counts)`,
/// D-major. The format holds no taxel geometry and no Parzen variant.
#include <ostream>
#include <string>
#include <vector>

#include "somasim/pps/learned_state.hpp"

namespace somasim::pps {

/// Writes `parts` (each a (D, TTC) map) as one `.ini` text. InputError for a distance-only part
/// (the format has no such maps).
void write_taxels2d_ini(const std::vector<LearnedState>& parts, std::ostream& out);

/// The same into `path`. InputError if it cannot be written.
void save_taxels2d_ini(const std::vector<LearnedState>& parts, const std::string& path);

/// True when `path` names a `.ini` learned file (by its extension), false for JSON.
bool is_ini_learned_file(const std::string& path);

}  // namespace somasim::pps
