#pragma once
/// @file
/// YARP Bottles in their text form, as yarpdatadumper writes them into data.log:
/// space-separated values; integers (`42`, `-3`), floating-point numbers (`0.5`, `1e-3`,
/// `inf`, `nan`), strings (bare words `left_arm`, or quoted `"two words"` with `\"` and `\\`
/// escapes), vocabularies (`[ok]`, kept as strings) and nested lists in parentheses
/// (`(1 2 (3 4))`). Binary blobs (`{...}`) are refused.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace somasim::recordings {

struct BottleValue;
/// A Bottle is a list of values.
using BottleList = std::vector<BottleValue>;

/// One value of a Bottle.
struct BottleValue {
  enum class Kind : std::uint8_t { kInt, kFloat, kString, kList };
  Kind kind = Kind::kInt;
  std::int64_t integer = 0;  ///< kInt
  double real = 0.0;         ///< kFloat
  std::string text;          ///< kString (a vocabulary keeps its brackets: "[ok]")
  BottleList list;           ///< kList
  int column = 1;            ///< 1-based column of the value in the parsed text

  bool is_number() const { return kind == Kind::kInt || kind == Kind::kFloat; }
  /// The value as a double (kInt converted); only for numbers.
  double number() const { return kind == Kind::kInt ? static_cast<double>(integer) : real; }
};

/// A syntax error at a 1-based column of the parsed text.
class BottleSyntaxError : public std::runtime_error {
 public:
  BottleSyntaxError(int column, const std::string& message)
      : std::runtime_error(message), column_(column) {}
  int column() const { return column_; }

 private:
  int column_;
};

/// Parses the text form of a Bottle (the whole of `text`; empty text is an empty Bottle).
/// `first_column` is the column of text[0] in its line (for the values' `column`).
/// Throws BottleSyntaxError at the offending column: an unbalanced parenthesis, an unterminated
/// string, a blob, a nesting deeper than 64 lists.
BottleList parse_bottle(std::string_view text, int first_column = 1);

/// The text form of `bottle` (numbers with full precision), which parse_bottle reads back equal.
std::string to_text(const BottleList& bottle);

/// The kind of a value in words: "an integer", "a number", "a string", "a list".
const char* kind_name(BottleValue::Kind kind);

}  // namespace somasim::recordings
