#include "somasim/pps/ini_import.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

#include "somasim/error.hpp"

namespace somasim::pps {

namespace {

// Bounds that keep every conversion to int defined; real files have a few hundred taxels.
constexpr int kMaxTaxels = 1'000'000;
constexpr int kMaxTaxelId = 1'000'000'000;

struct Section {
  std::string name;
  int line = 0;
  std::string modality;
  std::optional<int> n_taxels;
  std::optional<std::vector<double>> ext, ext_x, ext_y, bins;
  std::vector<std::pair<int, std::string>> taxel_lines;  // (line number, text)
};

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw InputError(path + ":" + std::to_string(line) + ": " + what);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool parse_double(const std::string& tok, double& out) {
  if (tok.empty()) return false;
  char* end = nullptr;
  out = std::strtod(tok.c_str(), &end);
  return end == tok.c_str() + tok.size() && std::isfinite(out);
}

// Splits "(a b c) (d e)" into groups; false on unbalanced or stray text.
bool parse_groups(const std::string& text, std::vector<std::vector<std::string>>& groups) {
  groups.clear();
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == '(') {
      const auto close = text.find(')', i);
      if (close == std::string::npos) return false;
      const std::string inner = text.substr(i + 1, close - i - 1);
      if (inner.find('(') != std::string::npos) return false;
      std::istringstream is(inner);
      std::vector<std::string> toks;
      for (std::string t; is >> t;) toks.push_back(t);
      groups.push_back(std::move(toks));
      i = close + 1;
    } else {
      return false;
    }
  }
  return true;
}

std::vector<double> parse_list(const std::string& path, int line, const std::string& key,
                               const std::string& rest, std::size_t expected) {
  std::vector<std::vector<std::string>> groups;
  if (!parse_groups(rest, groups) || groups.size() != 1)
    fail(path, line,
         "'" + key + "' is '" + rest + "', expected (" + std::to_string(expected) +
             " numbers) in parentheses");
  std::vector<double> out;
  for (const std::string& t : groups[0]) {
    double v = 0;
    if (!parse_double(t, v)) fail(path, line, "'" + key + "' has '" + t + "', expected a number");
    out.push_back(v);
  }
  if (out.size() != expected)
    fail(path, line,
         "'" + key + "' has " + std::to_string(out.size()) + " numbers, expected " +
             std::to_string(expected));
  return out;
}

std::vector<TaxelMap::Count> to_counts(const std::string& path, int line,
                                       const std::vector<std::string>& toks, const char* which,
                                       std::size_t expected, const GridSpec& g) {
  if (toks.size() != expected)
    fail(path, line,
         std::string(which) + " counts: " + std::to_string(toks.size()) + " values, expected " +
             std::to_string(expected) + " (" + std::to_string(g.d_bins) + " D bins x " +
             std::to_string(g.ttc_bins) + " TTC bins)");
  std::vector<TaxelMap::Count> out;
  out.reserve(expected);
  for (const std::string& t : toks) {
    double v = 0;
    if (!parse_double(t, v) || v < 0 || v != std::floor(v) || v > 4294967295.0)
      fail(path, line, std::string(which) + " count '" + t + "' is not a non-negative integer");
    out.push_back(static_cast<TaxelMap::Count>(v));
  }
  return out;
}

LearnedState build(const std::string& path, const Section& s, const ParzenSpec& parzen) {
  LearnedState st;
  st.body_part = s.name;
  st.parzen = parzen;
  if (s.ext && s.ext->size() != 4)  // read as 1D (2 numbers) before a later 'modality 2D'
    fail(path, s.line,
         "section [" + s.name + "]: 'ext' has " + std::to_string(s.ext->size()) +
             " numbers, expected 4 (dmin dmax tmin tmax) for a 2D section");
  if (s.ext) {
    st.grid.d_min = (*s.ext)[0];
    st.grid.d_max = (*s.ext)[1];
    st.grid.ttc_min = (*s.ext)[2];
    st.grid.ttc_max = (*s.ext)[3];
  } else if (s.ext_x && s.ext_y) {
    st.grid.d_min = (*s.ext_x)[0];
    st.grid.d_max = (*s.ext_x)[1];
    st.grid.ttc_min = (*s.ext_y)[0];
    st.grid.ttc_max = (*s.ext_y)[1];
  } else {
    fail(path, s.line, "section [" + s.name + "] has no 'ext' (or 'extX' and 'extY') line");
  }
  if (!s.bins) fail(path, s.line, "section [" + s.name + "] has no 'binsNum' line");
  const double bd = (*s.bins)[0], bt = (*s.bins)[1];
  const auto in_range = [](double v) {
    return v == std::floor(v) && v >= 1 && v <= kMaxBinsPerAxis;
  };
  if (!in_range(bd) || !in_range(bt))
    fail(path, s.line,
         "section [" + s.name + "]: binsNum must be integers in [1, " +
             std::to_string(kMaxBinsPerAxis) + "]");
  st.grid.d_bins = static_cast<int>(bd);
  st.grid.ttc_bins = static_cast<int>(bt);
  if (const std::string e = st.grid.validate(); !e.empty())
    fail(path, s.line, "section [" + s.name + "]: invalid grid: " + e);
  const std::size_t n = st.grid.size();
  for (const auto& [line, text] : s.taxel_lines) {
    std::istringstream is(text);
    std::string id_tok;
    is >> id_tok;
    double idv = 0;
    if (!parse_double(id_tok, idv) || idv != std::floor(idv) || std::abs(idv) > kMaxTaxelId)
      fail(path, line,
           "taxel id '" + id_tok + "' is not an integer in [-" + std::to_string(kMaxTaxelId) +
               ", " + std::to_string(kMaxTaxelId) + "]");
    std::string rest;
    std::getline(is, rest);
    std::vector<std::vector<std::string>> groups;
    if (!parse_groups(rest, groups) || groups.size() != 2)
      fail(path, line,
           "taxel line must be 'ID (" + std::to_string(n) + " positive counts) (" +
               std::to_string(n) + " negative counts)'");
    LearnedTaxel t;
    t.id = static_cast<int>(idv);
    t.pos = to_counts(path, line, groups[0], "positive", n, st.grid);
    t.neg = to_counts(path, line, groups[1], "negative", n, st.grid);
    st.taxels.push_back(std::move(t));
  }
  if (s.n_taxels && static_cast<std::size_t>(*s.n_taxels) != st.taxels.size())
    fail(path, s.line,
         "section [" + s.name + "] declares nTaxels " + std::to_string(*s.n_taxels) +
             " but lists " + std::to_string(st.taxels.size()) + " taxel lines");
  return st;
}

}  // namespace

std::vector<LearnedState> import_taxels2d_ini(const std::string& path, const ParzenSpec& parzen) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) &&
      !std::filesystem::is_regular_file(path, ec))  // (opening a FIFO blocks)
    throw InputError(path + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open for reading");
  return parse_taxels2d_ini(in, path, parzen);
}

std::vector<LearnedState> parse_taxels2d_ini(std::istream& in, const std::string& path,
                                             const ParzenSpec& parzen) {
  std::vector<Section> sections;
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const std::string l = trim(raw);
    if (l.empty() || l[0] == '#' || l[0] == ';') continue;
    if (l[0] == '[') {
      if (l.back() != ']' || l.size() < 3) fail(path, line, "malformed section header '" + l + "'");
      Section sec;
      sec.name = l.substr(1, l.size() - 2);
      sec.line = line;
      sections.push_back(std::move(sec));
      continue;
    }
    if (sections.empty()) fail(path, line, "'" + l + "' before the first [section]");
    Section& s = sections.back();
    std::istringstream is(l);
    std::string key;
    is >> key;
    std::string rest;
    std::getline(is, rest);
    rest = trim(rest);
    if (key == "modality") {
      s.modality = rest;
    } else if (key == "nTaxels") {
      double v = 0;
      if (!parse_double(rest, v) || v < 0 || v != std::floor(v) || v > kMaxTaxels)
        fail(path, line,
             "'nTaxels' is '" + rest + "', expected an integer in [0, " +
                 std::to_string(kMaxTaxels) + "]");
      s.n_taxels = static_cast<int>(v);
    } else if (key == "ext") {
      s.ext = parse_list(path, line, key, rest, s.modality == "1D" ? 2 : 4);
    } else if (key == "extX") {
      s.ext_x = parse_list(path, line, key, rest, 2);
    } else if (key == "extY") {
      s.ext_y = parse_list(path, line, key, rest, 2);
    } else if (key == "binsNum") {
      s.bins = parse_list(path, line, key, rest, 2);
    } else if (key == "size" || key == "Mapping") {
      // Physical taxel count / taxel-to-virtual-taxel mapping: not needed here.
    } else if (key[0] == '-' || (key[0] >= '0' && key[0] <= '9')) {
      s.taxel_lines.emplace_back(line, l);
    } else {
      fail(path, line, "unknown key '" + key + "'");
    }
  }
  std::vector<LearnedState> out;
  for (const Section& s : sections) {
    if (s.modality == "1D") continue;
    // Files from before the 1D maps existed (2014) have no modality line: they are 2D.
    if (s.modality != "2D" && !s.modality.empty())
      fail(path, s.line,
           "section [" + s.name + "] has modality '" + s.modality +
               "', expected 2D (1D sections are skipped)");
    out.push_back(build(path, s, parzen));
  }
  if (out.empty()) throw InputError(path + ": no 2D section found, expected at least one");
  return out;
}

}  // namespace somasim::pps
