#pragma once
/// @file
/// Where a value came from: a YAML file position or the command line.
#include <string>

namespace somasim {

/// A position in an input file. Lines and columns are 1-based; 0 means "unknown".
struct SourceLocation {
  std::string file;  ///< file path as given by the user, or "--set" for command-line overrides
  int line = 0;
  int column = 0;

  /// "file:line:column", or just "file" when the position is unknown.
  std::string str() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
};

}  // namespace somasim
