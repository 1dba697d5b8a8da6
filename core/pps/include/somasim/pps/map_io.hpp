#pragma once
/// @file
/// Save/load of learned PPS state as JSON (full description in README.md here). Three versions:
/// 1 for one body part's (D, TTC) maps, 2 for one body part's maps with the model named
/// (written for distance-only maps), 3 for several body parts in one file. One part is always
/// written as version 1 or 2, so that older readers still read it; every version is read.
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
/// fields only and its counts d_bins entries.
/// Version 3 holds several body parts, each a version-2 body (with "model") in "parts":
/// @code
/// {
///   "format": "somasim-pps-map", "version": 3,
///   "parts": [ {"body_part": "left_forearm", "model": "d_ttc", "grid": {...},
///               "parzen": {...}, "taxels": [...]},
///              {"body_part": "right_palm", ...} ]      // unique names, at least one part
/// }
/// @endcode
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "somasim/pps/learned_state.hpp"

namespace somasim::pps {

inline constexpr const char* kMapFormat = "somasim-pps-map";
inline constexpr int kMapFormatVersion = 1;       ///< (D, TTC) maps
inline constexpr int kMapFormatVersionModel = 2;  ///< with "model" (distance-only maps)
inline constexpr int kMapFormatVersionParts = 3;  ///< several body parts

/// What the caller expects of one loaded body part (unset: anything). From a version-3 file,
/// `body_part` selects the part (unset: the file must hold exactly one).
struct LoadExpectations {
  std::optional<std::string> body_part;
  std::optional<std::size_t> taxel_count;
  std::optional<PpsModel> model;
};

/// What the caller expects of a file read as several body parts.
struct PartsExpectations {
  /// The body parts wanted, in this order; the file must hold each (it may hold more). Empty:
  /// every part of the file, in file order.
  std::vector<std::string> body_parts;
  std::optional<PpsModel> model;  ///< of every returned part
};

/// One body part as version 1 ((D, TTC) maps) or 2 (distance-only maps).
nlohmann::json to_json(const LearnedState& state);
/// Several body parts (unique names) as version 3; exactly one part as to_json(parts[0]).
nlohmann::json to_json(const std::vector<LearnedState>& parts);
/// One body part from a file of any version. `source` names the origin (file path) in error
/// messages. Throws InputError.
LearnedState from_json(const nlohmann::json& j, const std::string& source,
                       const LoadExpectations& expect = {});
/// The body parts of a file of any version (a version 1/2 file is one part). InputError
/// `<source>: has no body part "b" (it has: a), expected every body part of "a b"` when a wanted
/// part is missing; with one part wanted from a one-part file: `body part is "a", expected "b"`.
std::vector<LearnedState> parts_from_json(const nlohmann::json& j, const std::string& source,
                                          const PartsExpectations& expect = {});

/// Writes `state` to `path` (pretty-printed). InputError if the file cannot be written.
void save_learned_state(const LearnedState& state, const std::string& path);
/// Writes several body parts to one file (to_json(parts)).
void save_learned_parts(const std::vector<LearnedState>& parts, const std::string& path);
/// Reads `path`. InputError naming the file, what is wrong and what was expected.
LearnedState load_learned_state(const std::string& path, const LoadExpectations& expect = {});
/// Reads `path` as several body parts (see parts_from_json).
std::vector<LearnedState> load_learned_parts(const std::string& path,
                                             const PartsExpectations& expect = {});
/// The same from the text of such a file; `source` names it in messages.
std::vector<LearnedState> parse_learned_parts(const std::string& text, const std::string& source,
                                              const PartsExpectations& expect = {});

}  // namespace somasim::pps
