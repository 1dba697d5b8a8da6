#include "somasim/recordings/yarp_bottle.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace somasim::recordings {

namespace {

constexpr int kMaxDepth = 64;

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
bool ends_token(char c) {
  return is_space(c) || c == '(' || c == ')';
}

BottleValue word_value(std::string_view word, int column) {
  BottleValue v;
  v.column = column;
  std::int64_t i = 0;
  const char* first = word.data();
  const char* last = word.data() + word.size();
  if (auto [p, ec] = std::from_chars(first, last, i); ec == std::errc() && p == last) {
    v.kind = BottleValue::Kind::kInt;
    v.integer = i;
    return v;
  }
  double d = 0.0;
  const char* start = first != last && *first == '+' ? first + 1 : first;
  if (auto [p, ec] = std::from_chars(start, last, d); ec == std::errc() && p == last) {
    v.kind = BottleValue::Kind::kFloat;
    v.real = d;
    return v;
  }
  v.kind = BottleValue::Kind::kString;
  v.text = std::string(word);
  return v;
}

class Parser {
 public:
  Parser(std::string_view text, int first_column) : text_(text), first_column_(first_column) {}

  BottleList parse() {
    BottleList out = list(0);
    if (pos_ < text_.size())  // list() stops only at the end or at a ')'
      fail(pos_, "unbalanced ')': no list is open here");
    return out;
  }

 private:
  int column(std::size_t at) const { return first_column_ + static_cast<int>(at); }
  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw BottleSyntaxError(column(at), message);
  }

  BottleList list(int depth) {
    BottleList out;
    while (true) {
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (pos_ >= text_.size() || text_[pos_] == ')') return out;
      const std::size_t start = pos_;
      const char c = text_[pos_];
      if (c == '(') {
        if (depth + 1 > kMaxDepth)
          fail(start, fmt::format("lists nested deeper than {}", kMaxDepth));
        ++pos_;
        BottleValue v;
        v.kind = BottleValue::Kind::kList;
        v.column = column(start);
        v.list = list(depth + 1);
        if (pos_ >= text_.size()) fail(start, "unbalanced '(': the list is never closed");
        ++pos_;  // ')'
        out.push_back(std::move(v));
      } else if (c == '"') {
        out.push_back(quoted(start));
      } else if (c == '{') {
        fail(start, "binary blobs ('{...}') are not supported");
      } else if (c == '[') {
        const std::size_t close = text_.find(']', pos_);
        if (close == std::string_view::npos) fail(start, "unterminated vocabulary: no ']'");
        BottleValue v;
        v.kind = BottleValue::Kind::kString;
        v.column = column(start);
        v.text = std::string(text_.substr(start, close + 1 - start));
        pos_ = close + 1;
        out.push_back(std::move(v));
      } else {
        while (pos_ < text_.size() && !ends_token(text_[pos_])) ++pos_;
        out.push_back(word_value(text_.substr(start, pos_ - start), column(start)));
      }
    }
  }

  BottleValue quoted(std::size_t start) {
    BottleValue v;
    v.kind = BottleValue::Kind::kString;
    v.column = column(start);
    ++pos_;
    while (true) {
      if (pos_ >= text_.size()) fail(start, "unterminated string: no closing '\"'");
      const char c = text_[pos_++];
      if (c == '"') return v;
      if (c == '\\' && pos_ < text_.size()) {
        const char e = text_[pos_++];
        v.text += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e;
      } else {
        v.text += c;
      }
    }
  }

  std::string_view text_;
  int first_column_;
  std::size_t pos_ = 0;
};

bool needs_quotes(const std::string& s) {
  if (s.empty()) return true;
  if (s.front() == '[' && s.back() == ']' && s.find(']') == s.size() - 1) return false;
  for (char c : s)
    if (is_space(c) || c == '(' || c == ')' || c == '"' || c == '\\' || c == '{' || c == '[')
      return true;
  // A bare word that would read back as a number must be quoted.
  return word_value(s, 1).kind != BottleValue::Kind::kString;
}

void append(std::string& out, const BottleValue& v) {
  switch (v.kind) {
    case BottleValue::Kind::kInt:
      out += fmt::format("{}", v.integer);
      break;
    case BottleValue::Kind::kFloat:
      if (std::isnan(v.real)) {
        out += "nan";
      } else if (std::isinf(v.real)) {
        out += v.real > 0 ? "inf" : "-inf";
      } else {
        std::string s = fmt::format("{}", v.real);
        if (s.find_first_of(".en") == std::string::npos) s += ".0";  // stays a float
        out += s;
      }
      break;
    case BottleValue::Kind::kString:
      if (!needs_quotes(v.text)) {
        out += v.text;
      } else {
        out += '"';
        for (char c : v.text) {
          if (c == '"' || c == '\\') out += '\\';
          if (c == '\n') {
            out += "\\n";
            continue;
          }
          out += c;
        }
        out += '"';
      }
      break;
    case BottleValue::Kind::kList:
      out += '(';
      out += to_text(v.list);
      out += ')';
      break;
  }
}

}  // namespace

BottleList parse_bottle(std::string_view text, int first_column) {
  return Parser(text, first_column).parse();
}

std::string to_text(const BottleList& bottle) {
  std::string out;
  for (std::size_t i = 0; i < bottle.size(); ++i) {
    if (i) out += ' ';
    append(out, bottle[i]);
  }
  return out;
}

const char* kind_name(BottleValue::Kind kind) {
  switch (kind) {
    case BottleValue::Kind::kInt:
      return "an integer";
    case BottleValue::Kind::kFloat:
      return "a number";
    case BottleValue::Kind::kString:
      return "a string";
    case BottleValue::Kind::kList:
      return "a list";
  }
  return "a value";
}

}  // namespace somasim::recordings
