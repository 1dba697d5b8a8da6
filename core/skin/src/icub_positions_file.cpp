#include "somasim/skin/icub_positions_file.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "somasim/error.hpp"

namespace somasim::skin {
namespace {

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

bool is_key_line(const std::string& first_word) {
  return first_word == "name" || first_word == "spatial_sampling" || first_word == "taxel2Repr" ||
         first_word == "[calibration]";
}

std::string strip_comment(const std::string& line) {
  const auto hash = line.find_first_of("#;");
  return hash == std::string::npos ? line : line.substr(0, hash);
}

// The integers of "taxel2Repr (3 3 -1 ...)"; the list may span lines (read until ')').
std::vector<int> read_representatives(std::string text, std::ifstream& in, int& line_no,
                                      const std::string& where) {
  while (text.find(')') == std::string::npos) {
    std::string more;
    if (!std::getline(in, more))
      throw InputError(where + "the taxel2Repr list is never closed (expected ')')");
    ++line_no;
    text += ' ' + strip_comment(more);
  }
  const auto open = text.find('('), close = text.find(')');
  if (open == std::string::npos || close < open)
    throw InputError(where + "expected 'taxel2Repr (ID ID ...)' with the ids in parentheses");
  std::vector<int> ids;
  for (const std::string& w : words(text.substr(open + 1, close - open - 1))) {
    int v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || end != w.data() + w.size() || v < -1)
      throw InputError(where + fmt::format("taxel2Repr entry '{}' is not an integer >= -1", w));
    ids.push_back(v);
  }
  return ids;
}

}  // namespace

bool is_icub_positions_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> w = words(strip_comment(line));
    if (w.empty()) continue;
    return is_key_line(w[0]);
  }
  return false;
}

SkinLayout load_icub_positions_file(const std::filesystem::path& file, const std::string& body_part,
                                    int link) {
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in)
    throw InputError(name + ": cannot open the taxel positions file (" +
                     (std::filesystem::exists(file) ? "not readable" : "no such file") + ")");
  SkinLayout layout;
  layout.body_part = body_part;
  layout.link = link;
  std::vector<int> representatives;
  bool in_rows = false;
  int row = 0;
  std::string text;
  for (int line_no = 1; std::getline(in, text); ++line_no) {
    const std::string where = fmt::format("{}:{}: ", name, line_no);
    text = strip_comment(text);
    const std::vector<std::string> w = words(text);
    if (w.empty()) continue;
    if (!in_rows && is_key_line(w[0])) {
      if (w[0] == "taxel2Repr") representatives = read_representatives(text, in, line_no, where);
      in_rows = w[0] == "[calibration]";
      continue;
    }
    if (w[0].front() == '[') {  // another section: its rows are not taxels
      in_rows = false;
      continue;
    }
    if (!in_rows && !std::isdigit(static_cast<unsigned char>(w[0].front())) &&
        w[0].front() != '-' && w[0].front() != '.')
      continue;  // another key of the header
    in_rows = true;
    if (w.size() != 6)
      throw InputError(where + fmt::format("expected 6 numbers (x y z nx ny nz) for taxel {}, got "
                                           "{} fields",
                                           row, w.size()));
    double v[6];
    for (int k = 0; k < 6; ++k) {
      const std::string& f = w[static_cast<std::size_t>(k)];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v[k]);
      if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v[k]))
        throw InputError(where + fmt::format("'{}' is not a finite number (taxel {})", f, row));
    }
    const int id = row++;
    const Eigen::Vector3d p(v[0], v[1], v[2]), n(v[3], v[4], v[5]);
    if (p.isZero(0.0) && n.isZero(0.0)) continue;  // no taxel at this id
    if (n.norm() < 1e-9)
      throw InputError(where + fmt::format("taxel {} has a position but a zero normal", id));
    layout.ids.push_back(id);
    layout.positions.push_back(p);
    layout.normals.push_back(n.normalized());
  }
  if (layout.ids.empty())
    throw InputError(name + ": no taxels (expected rows 'x y z nx ny nz' after [calibration])");
  std::vector<int> keys;
  keys.reserve(layout.ids.size());
  for (int id : layout.ids) {
    const auto k = static_cast<std::size_t>(id);
    keys.push_back(k < representatives.size() && representatives[k] >= 0 ? representatives[k] : id);
  }
  group_by_key(layout, keys);
  return layout;
}

}  // namespace somasim::skin
