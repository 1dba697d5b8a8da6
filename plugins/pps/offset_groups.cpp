#include "offset_groups.hpp"

#include <algorithm>
#include <sstream>

#include "somasim/diagnostics.hpp"
#include "somasim/error.hpp"

namespace somasim::plugins {

namespace {

std::optional<Eigen::Vector3d> parse_side(const std::string& entry, const std::string& token) {
  static const char* kAxes[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  const auto* it = std::find(std::begin(kAxes), std::end(kAxes), token);
  if (it == std::end(kAxes))
    throw InputError("offset_groups entry '" + entry + "': side '" + token +
                     "' is not one of +x -x +y -y +z -z (the taxel normal's direction in the "
                     "part's link frame)");
  const auto k = static_cast<int>(it - std::begin(kAxes));
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  axis[k / 2] = k % 2 == 0 ? 1.0 : -1.0;
  return axis;
}

}  // namespace

std::vector<OffsetGroup> parse_offset_groups(const std::string& text,
                                             const std::vector<std::string>& parts) {
  std::vector<OffsetGroup> groups;
  std::stringstream all(text);
  std::string entry;
  while (std::getline(all, entry, ',')) {
    const auto first = entry.find_first_not_of(" \t\n");
    if (first == std::string::npos) continue;
    entry = entry.substr(first, entry.find_last_not_of(" \t\n") - first + 1);
    const auto colon = entry.find(':');
    if (colon == std::string::npos || colon == 0)
      throw InputError("offset_groups entry '" + entry +
                       "': expected 'name: part [side]', e.g. 'inner_forearm: left_forearm +z'");
    OffsetGroup g;
    g.name = entry.substr(0, colon);
    std::stringstream rest(entry.substr(colon + 1));
    std::string side;
    rest >> g.part >> side;
    std::string extra;
    if (g.part.empty() || (rest >> extra))
      throw InputError("offset_groups entry '" + entry +
                       "': expected 'name: part [side]', e.g. 'inner_forearm: left_forearm +z'");
    if (std::find(parts.begin(), parts.end(), g.part) == parts.end())
      throw InputError("offset_groups entry '" + entry + "': '" + g.part +
                       "' is not a body_part of this learner" + did_you_mean(g.part, parts) +
                       " (its parts: " + join_names(parts) + ")");
    if (!side.empty()) g.side = parse_side(entry, side);
    for (const auto& other : groups)
      if (other.name == g.name)
        throw InputError("offset_groups: group '" + g.name + "' is named twice");
    groups.push_back(std::move(g));
  }
  return groups;
}

}  // namespace somasim::plugins
