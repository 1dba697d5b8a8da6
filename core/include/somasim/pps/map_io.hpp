#pragma once
/// @file
/// Save/load of learned PPS state as JSON. Format (version 1 for (D, TTC) maps, version 2 for
/// distance-only maps; see README.md here):
/// @code
/// {
///   "format": "somasim-pps-map", "version": 1,
///   "body_part": "l_forearm",
///   "grid":   {"d_min": -0.1, "d_max": 0.2, "d_bins": 8, "ttc_min": 0.0, "ttc_max": 1.2,
///              "ttc_bins": 4},                        // [m], [s]
///   "parzen": {"sigma_scale": 0.75, "anchor": "lower_edge"},   // or "centre"
///   "taxels": [ {"id": 3, "position": [x, y, z], "normal": [nx, ny, nz],   // link frame, [m]
///                "pos": [32 non-negative integers], "neg": [32 ...]} ]    // D-major
/// }
/// @endcode
/// Version 2 adds "model": "d_ttc" | "distance_only"; a distance-only file's grid has the D
/// fields only and its counts d_bins entries. (D, TTC) maps are written as version 1, so that
/// older readers still read them; both versions are read.
#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "somasim/pps/learned_state.hpp"

namespace somasim::pps {

inline constexpr const char* kMapFormat = "somasim-pps-map";
inline constexpr int kMapFormatVersion = 1;       ///< (D, TTC) maps
inline constexpr int kMapFormatVersionModel = 2;  ///< with "model" (distance-only maps)

/// What the caller expects of a loaded file (unset: anything).
struct LoadExpectations {
  std::optional<std::string> body_part;
  std::optional<std::size_t> taxel_count;
  std::optional<PpsModel> model;
};

nlohmann::json to_json(const LearnedState& state);
/// `source` names the origin (file path) in error messages. Throws InputError.
LearnedState from_json(const nlohmann::json& j, const std::string& source,
                       const LoadExpectations& expect = {});

/// Writes `state` to `path` (pretty-printed). InputError if the file cannot be written.
void save_learned_state(const LearnedState& state, const std::string& path);
/// Reads `path`. InputError naming the file, what is wrong and what was expected.
LearnedState load_learned_state(const std::string& path, const LoadExpectations& expect = {});

}  // namespace somasim::pps
