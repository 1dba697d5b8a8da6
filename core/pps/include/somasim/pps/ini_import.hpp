#pragma once
/// @file
/// Import of the original iCub peripersonalSpace `taxels2D_*.ini` files (learned 2-D taxels).
///
/// Per section `[part]`: `modality 2D`, `nTaxels N`, `ext (dmin dmax tmin tmax)` (older files:
/// `extX (dmin dmax)` and `extY (tmin tmax)`), `binsNum (nd nt)`, `size`, `Mapping (...)`
/// (ignored), then N lines `ID (nd*nt positive counts) (nd*nt negative counts)`, D-major. Sections
/// with `modality 1D` are skipped; a section without a modality line (2014 files) is 2D. The files
/// carry no taxel geometry: positions are set to 0 and normals to +z (link frame); take the
/// geometry from the skinGui position files.
#include <istream>
#include <string>
#include <vector>

#include "somasim/pps/learned_state.hpp"

namespace somasim::pps {

/// One LearnedState per 2-D section, grid from the file, Parzen variant `parzen` (default: the
/// released code's). InputError naming file:line and the problem.
std::vector<LearnedState> import_taxels2d_ini(const std::string& path,
                                              const ParzenSpec& parzen = ParzenSpec::code());

/// The same from a stream; `source` names it in messages.
std::vector<LearnedState> parse_taxels2d_ini(std::istream& in, const std::string& source,
                                             const ParzenSpec& parzen = ParzenSpec::code());

}  // namespace somasim::pps
