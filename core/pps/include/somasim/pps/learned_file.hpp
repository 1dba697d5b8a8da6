#pragma once
/// @file
/// Learned-map files of either format, chosen by extension: somasim JSON (map_io.hpp: geometry,
/// model, Parzen variant, any number of parts) or the iCub's `taxels2D_*.ini` (ini_import.hpp,
/// ini_export.hpp: (D, TTC) counts only, no geometry).
#include <string>
#include <vector>

#include "somasim/pps/learned_state.hpp"
#include "somasim/pps/map_io.hpp"

namespace somasim::pps {

/// A file's parts and whether they carry taxel geometry (an `.ini` file does not: positions 0,
/// normals +z; take them from the skin).
struct LearnedFile {
  std::vector<LearnedState> parts;
  bool has_geometry = true;
};

/// Reads `path` (`.ini`: the iCub format, Parzen variant `ini_parzen`; else JSON) and returns the
/// parts `expect` asks for, in its order. InputError naming the file, what is wrong and what was
/// expected (a missing part lists the parts the file has).
LearnedFile load_learned_file(const std::string& path, const PartsExpectations& expect,
                              const ParzenSpec& ini_parzen);

/// Writes `parts` to `path` in the format its extension names (`.ini` or JSON).
void save_learned_file(const std::vector<LearnedState>& parts, const std::string& path);

}  // namespace somasim::pps
