#pragma once
/// @file
/// Collects every input error of an experiment file so that they are reported together.
#include <string>
#include <vector>

#include "somasim/source_location.hpp"

namespace somasim {

/// One input error: where, which node and key (either may be empty), and what is wrong.
struct Diagnostic {
  SourceLocation where;
  std::string node;
  std::string key;
  std::string message;  ///< what is wrong and what was expected

  /// "file:line:col: node 'n', key 'k': message".
  std::string str() const;
};

/// Accumulates diagnostics; throw_if_any() raises one InputError listing them all.
class Diagnostics {
 public:
  void add(SourceLocation where, std::string node, std::string key, std::string message);
  bool empty() const { return total_ == 0; }
  /// The first kMaxKept problems (memory stays bounded whatever the input).
  const std::vector<Diagnostic>& items() const { return items_; }
  std::size_t total() const { return total_; }
  /// Throws InputError: the single message, or "N errors:" followed by one line per error in
  /// file order, at most kMaxShown of them ("... and M more").
  void throw_if_any() const;

  static constexpr std::size_t kMaxKept = 1000;
  static constexpr std::size_t kMaxShown = 50;

 private:
  std::vector<Diagnostic> items_;
  std::size_t total_ = 0;
};

/// The candidate closest to `name` by edit distance, or "" when none is reasonably close.
std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates);

/// " (did you mean 'x'?)" when a close candidate exists, else "".
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

/// "a, b, c" — candidates joined for messages.
std::string join_names(const std::vector<std::string>& names);

}  // namespace somasim
