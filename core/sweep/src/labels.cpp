#include "somasim/sweep/labels.hpp"

#include <array>
#include <utility>

namespace somasim::sweep {

namespace {

// Longest first: "_m_s" before "_s", "_mm" and "_ms" before "_m" and "_s".
constexpr std::array<std::pair<const char*, const char*>, 10> kUnitSuffixes = {{
    {"_per_s", "1/s"},
    {"_m_s", "m/s"},
    {"_deg", "deg"},
    {"_rad", "rad"},
    {"_mm", "mm"},
    {"_ms", "ms"},
    {"_hz", "Hz"},
    {"_m", "m"},
    {"_s", "s"},
    {"_px", "px"},
}};

std::string words(std::string name) {
  for (char& c : name)
    if (c == '_' || c == '.') c = ' ';
  return name;
}

}  // namespace

std::string metric_label(const std::string& metric) {
  std::string name = metric;
  if (name.rfind("nodes.", 0) == 0) name = name.substr(6);
  for (const auto& [suffix, unit] : kUnitSuffixes) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0)
      return words(name.substr(0, name.size() - s.size())) + " [" + unit + "]";
  }
  return words(name);
}

std::string parameter_label(const std::string& path, const std::string& doc,
                            const std::string& unit) {
  const std::size_t dot = path.rfind('.');
  std::string label = dot == std::string::npos ? path : path.substr(dot + 1);
  if (!unit.empty()) label += " [" + unit + "]";
  if (doc.empty()) return label;
  std::string text = doc;
  constexpr std::size_t kMax = 70;
  if (text.size() > kMax) {
    const std::size_t cut = text.rfind(' ', kMax);
    text = text.substr(0, cut == std::string::npos ? kMax : cut) + " …";
  }
  return label + ": " + text;
}

}  // namespace somasim::sweep
