#include "yaml_values.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim {

namespace {

// The YAML documents in `text`, counted from its lines (YAML::LoadAll can loop forever on some
// malformed input, e.g. ",(#"): a document marker "---" or "..." starts a line (column 0) and is
// followed by white space or the line's end; a line with content (not blank, not a comment, not
// a % directive) after a "---" that follows content, or after a "...", is in a new document.
std::size_t yaml_documents(const std::string& text) {
  const auto content = [](std::string_view s) {
    const auto i = s.find_first_not_of(" \t\r");
    return i != std::string_view::npos && s[i] != '#';
  };
  const auto marker = [](std::string_view line, std::string_view m) {
    return line.substr(0, 3) == m &&
           (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
  };
  std::size_t documents = 0;
  bool open = false;  // the current document has content or was started by "---"
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    if (marker(line, "---")) {
      if (open) ++documents;
      open = true;  // an explicit document, even an empty one
    } else if (marker(line, "...")) {
      if (open) ++documents;
      open = false;
    } else if (!open && !line.empty() && line[0] == '%') {
      continue;  // a directive
    } else if (content(line)) {
      open = true;
    }
  }
  return documents + (open ? 1 : 0);
}

}  // namespace

YAML::Node load_one_document(const std::string& text) {
  const std::size_t documents = yaml_documents(text);
  if (documents > 1)
    throw InputError(
        fmt::format("holds {} YAML documents (separated by '---'); expected one", documents));
  return YAML::Load(text);
}

std::string describe_yaml(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      // (not `"'" + text + "'"`: GCC 12 warns falsely on it, -Wrestrict)
      return fmt::format("'{}'", escape_control_bytes(node.Scalar()));
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Null:
      return "nothing";
    default:
      return "an undefined value";
  }
}

std::optional<double> parse_double(const std::string& text) {
  if (text == ".nan" || text == ".NaN" || text == ".NAN" || text == "nan" || text == "NaN")
    return std::nan("");
  if (text == ".inf" || text == ".Inf" || text == "+.inf" || text == "inf") return HUGE_VAL;
  if (text == "-.inf" || text == "-.Inf" || text == "-inf") return -HUGE_VAL;
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parse_int(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return static_cast<std::int64_t>(v);
}

std::string escape_control_bytes(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n') || u == 0x7f)
      out += fmt::format("\\x{:02x}", u);
    else
      out += c;
  }
  return out;
}

std::optional<std::uint64_t> parse_seed(const std::string& text) {
  if (text.empty() || text.size() > 20 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;
  return static_cast<std::uint64_t>(v);
}

std::optional<bool> parse_bool(const std::string& text) {
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  return std::nullopt;
}

}  // namespace somasim

namespace somasim::detail {

SourceLocation LocationMap::of(const YAML::Node& node) const {
  for (const auto& [n, text] : overrides_)
    if (n.is(node)) return {"--set " + text, 0, 0};
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {file_, 0, 0};
  return {file_, mark.line + 1, mark.column + 1};
}

std::string expectation(const ParamSpec& spec) {
  std::string e = param_type_name(spec.type);
  if (spec.type == ParamType::DoubleList && spec.list_size)
    e = fmt::format("a list of {} numbers", *spec.list_size);
  if (spec.type == ParamType::StringList && spec.list_size)
    e = fmt::format("a list of {} words", *spec.list_size);
  if (!spec.unit.empty()) e += " [" + spec.unit + "]";
  if (spec.min && spec.max)
    e += fmt::format(" in [{}, {}]", *spec.min, *spec.max);
  else if (spec.min)
    e += fmt::format(" >= {}", *spec.min);
  else if (spec.max)
    e += fmt::format(" <= {}", *spec.max);
  if (!spec.choices.empty()) {
    e += ": one of ";
    for (std::size_t i = 0; i < spec.choices.size(); ++i) e += (i ? ", " : "") + spec.choices[i];
  }
  return e;
}

namespace {

// Words of a StringList given as one scalar: separated by spaces, tabs, newlines or commas.
std::vector<std::string> split_words(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (char c : text) {
    if (c == ' ' || c == ',' || c == '\t' || c == '\n' || c == '\r') {
      if (!word.empty()) words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

std::optional<ParamValue> to_string_list(const YAML::Node& node, const ParamSpec& spec,
                                         std::string& problem) {
  std::vector<std::string> list;
  if (node.IsScalar()) {
    list = split_words(node.Scalar());
  } else if (node.IsSequence()) {
    for (const auto& item : node) {
      if (!item.IsScalar() || item.Scalar().empty() ||
          split_words(item.Scalar()) != std::vector<std::string>{item.Scalar()}) {
        problem = "expected " + expectation(spec) + ", got an element " + describe_yaml(item);
        return std::nullopt;
      }
      list.push_back(item.Scalar());
    }
  } else if (!node.IsNull()) {
    problem = "expected " + expectation(spec) + ", got " + describe_yaml(node);
    return std::nullopt;
  }
  for (const auto& word : list)
    if (!spec.choices.empty() &&
        std::find(spec.choices.begin(), spec.choices.end(), word) == spec.choices.end()) {
      problem = "expected " + expectation(spec) + ", got an element '" + word + "'";
      return std::nullopt;
    }
  if (spec.list_size && list.size() != *spec.list_size) {
    problem = fmt::format("expected {}, got {} words", expectation(spec), list.size());
    return std::nullopt;
  }
  if (spec.max_list_size && list.size() > *spec.max_list_size) {
    problem = fmt::format("expected at most {} words, got {}", *spec.max_list_size, list.size());
    return std::nullopt;
  }
  return list;
}

bool check_number(double v, const ParamSpec& spec, const std::string& raw, std::string& problem) {
  if (!std::isfinite(v)) {
    problem = "expected a finite number, got '" + raw + "'";
    return false;
  }
  if ((spec.min && v < *spec.min) || (spec.max && v > *spec.max)) {
    problem = "value " + raw + " is out of range; expected " + expectation(spec);
    return false;
  }
  return true;
}
}  // namespace

std::optional<ParamValue> to_param_value(const YAML::Node& node, const ParamSpec& spec,
                                         std::string& problem) {
  const std::string got = describe_yaml(node);
  if (spec.type == ParamType::StringList) return to_string_list(node, spec, problem);
  if (spec.type == ParamType::DoubleList) {
    if (!node.IsSequence()) {
      problem = "expected " + expectation(spec) + ", got " + got;
      return std::nullopt;
    }
    std::vector<double> list;
    for (const auto& item : node) {
      const auto v = item.IsScalar() ? parse_double(item.Scalar()) : std::nullopt;
      if (!v) {
        problem = "expected " + expectation(spec) + ", got an element " + describe_yaml(item);
        return std::nullopt;
      }
      if (!check_number(*v, spec, item.Scalar(), problem)) return std::nullopt;
      list.push_back(*v);
    }
    if (spec.list_size && list.size() != *spec.list_size) {
      problem = fmt::format("expected {}, got {} numbers", expectation(spec), list.size());
      return std::nullopt;
    }
    if (spec.max_list_size && list.size() > *spec.max_list_size) {
      problem =
          fmt::format("expected at most {} numbers, got {}", *spec.max_list_size, list.size());
      return std::nullopt;
    }
    return list;
  }
  if (spec.type == ParamType::String && spec.map_as_text && node.IsMap()) {
    std::string text;
    for (const auto& kv : node) {
      if (!kv.first.IsScalar() || !kv.second.IsScalar()) {
        problem = "expected " + expectation(spec) +
                  " or a map of names to values, got a map "
                  "holding " +
                  describe_yaml(kv.first.IsScalar() ? kv.second : kv.first);
        return std::nullopt;
      }
      text += (text.empty() ? "" : ", ") + kv.first.Scalar() + ": " + kv.second.Scalar();
    }
    return text;
  }
  if (!node.IsScalar()) {
    problem = "expected " + expectation(spec) + ", got " + got;
    if (spec.type == ParamType::String && node.IsMap())
      problem += " (a text value holding ':' needs quotes: 'a: 1, b: 2')";
    return std::nullopt;
  }
  const std::string& text = node.Scalar();
  switch (spec.type) {
    case ParamType::Bool:
      if (auto b = parse_bool(text)) return *b;
      break;
    case ParamType::Int:
      if (auto i = parse_int(text)) {
        if ((spec.int_min && *i < *spec.int_min) || (spec.int_max && *i > *spec.int_max)) {
          problem = fmt::format(
              "value {} is out of range; expected {} (the parameter holds integers in [{}, {}])",
              text, expectation(spec), spec.int_min.value_or(INT64_MIN),
              spec.int_max.value_or(INT64_MAX));
          return std::nullopt;
        }
        if (!check_number(static_cast<double>(*i), spec, text, problem)) return std::nullopt;
        return *i;
      }
      break;
    case ParamType::Double:
      if (auto d = parse_double(text)) {
        if (!check_number(*d, spec, text, problem)) return std::nullopt;
        return *d;
      }
      break;
    case ParamType::String:
      if (!spec.choices.empty() &&
          std::find(spec.choices.begin(), spec.choices.end(), text) == spec.choices.end()) {
        problem = "expected " + expectation(spec) + ", got " + got;
        return std::nullopt;
      }
      return text;
    case ParamType::DoubleList:
    case ParamType::StringList:
      break;
  }
  problem = "expected " + expectation(spec) + ", got " + got;
  return std::nullopt;
}

}  // namespace somasim::detail
