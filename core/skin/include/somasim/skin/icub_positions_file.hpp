#pragma once
/// @file
/// The iCub's taxel positions files (icub-main app/skinGui/conf/positions/*.txt), read as skin
/// layouts:
/// @code
///   name                l_forearm
///   spatial_sampling    taxel
///   taxel2Repr          (3 3 3 ... -1 -1 ...)   # module representative per taxel, -1 none
///   [calibration]
///   -0.031 -0.075  0.008 -0.976  0.065  0.146    # taxel 0: x y z [m], normal, link frame
///   0 0 0 0 0 0                                  # taxel 1: all zero = no taxel here
/// @endcode
/// Row k of the [calibration] section is taxel id k; all-zero rows are left out. Taxels with a
/// representative are grouped into one virtual taxel per representative (virtual id = the
/// representative's id, as the iCub's skinManager publishes); a taxel without one (-1, or no
/// taxel2Repr list) is its own virtual taxel. Positions are in the frame of the skin part's
/// link in the iCub's kinematics (its DH link frame): the robot link the layout is put on must
/// have that frame.
#include <filesystem>
#include <string>

#include "somasim/skin/skin_layout.hpp"

namespace somasim::skin {

/// True when `file` starts like a positions file (a `name`, `spatial_sampling` or
/// `taxel2Repr` key, or a `[calibration]` section, before any row of numbers).
bool is_icub_positions_file(const std::filesystem::path& file);

/// Reads a positions file for `body_part` on link `link`. Throws InputError "FILE:LINE: ..." for
/// a row that is not 6 finite numbers, a taxel with a position but a zero normal, a taxel2Repr
/// list that is not a parenthesised list of integers >= -1, and a file without any taxel.
SkinLayout load_icub_positions_file(const std::filesystem::path& file, const std::string& body_part,
                                    int link);

}  // namespace somasim::skin
