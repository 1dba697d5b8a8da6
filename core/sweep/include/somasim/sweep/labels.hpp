#pragma once
/// @file
/// Words for a sweep figure's axes: a metric's name read as a quantity with its unit (from the
/// project's name suffixes, e.g. `offset_error_max_m` -> "offset error max [m]"), and a swept
/// parameter's label from its declared doc and unit.
#include <optional>
#include <string>

namespace somasim::sweep {

/// "offset_error_max_m" -> "offset error max [m]", "triggered_rate" -> "triggered rate",
/// "nodes.pps.rate" -> "pps rate"; suffixes read as units: _m, _mm, _s, _ms, _deg, _rad, _hz,
/// _px, _m_s (m/s), _per_s (1/s). A flat name's node prefix ("filter.x_mm") is kept as words.
std::string metric_label(const std::string& metric);

/// The label of the swept path `path` (e.g. "nodes.thrower.params.offset") given the parameter's
/// doc and unit (either may be empty): "offset [m]: start offset from the taxel", the doc cut at
/// a word to about 50 characters; without a doc, the last path component with its unit.
std::string parameter_label(const std::string& path, const std::string& doc,
                            const std::string& unit);

}  // namespace somasim::sweep
