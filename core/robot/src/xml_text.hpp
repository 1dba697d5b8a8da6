#pragma once
// Internal: text helpers of the robot exporters (URDF, MJCF).
#include <string>

#include <fmt/format.h>

namespace somasim::robot::detail {

/// `text` with XML's five special characters escaped (for attribute values and text).
inline std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  return out;
}

/// A double written so that reading it back gives the same double (17 significant digits).
inline std::string num(double v) {
  return fmt::format("{:.17g}", v);
}

}  // namespace somasim::robot::detail
