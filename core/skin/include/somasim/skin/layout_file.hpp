#pragma once
/// @file
/// Skin layout files: one physical taxel per line, in the frame of the link the skin is on.
///
/// @code
///   # id  x [m]   y [m]   z [m]   nx     ny     nz     [module]
///   0     -0.021  -0.030  0.000   -1.0   0.0    0.0    0
///   1     -0.021  -0.035  0.000   -1.0   0.0    0.0    0
/// @endcode
/// Fields are separated by spaces, tabs or commas; `#` starts a comment; blank lines are
/// ignored. `id` is a unique integer >= 0; the normal must be non-zero and is normalised.
/// The optional 8th column is the taxel's module (virtual taxel id, integer >= 0): all lines
/// must then have it. Without it, every taxel is its own virtual taxel (same id) - the format
/// of a list of triangle centres.
///
/// load_layout_file also reads the iCub's own taxel positions files (icub_positions_file.hpp),
/// recognised by their header.
#include <filesystem>
#include <string>

#include "somasim/skin/skin_layout.hpp"

namespace somasim::skin {

/// Reads a layout file for `body_part` on link `link`. Throws InputError "FILE:LINE: ..."
/// (or "FILE: ..." for a missing/empty file) on bad input.
SkinLayout load_layout_file(const std::filesystem::path& file, const std::string& body_part,
                            int link);

/// Writes `layout` in the same format (8 columns; module = virtual id). Throws InputError when
/// the file cannot be written.
void save_layout_file(const SkinLayout& layout, const std::filesystem::path& file);

}  // namespace somasim::skin
