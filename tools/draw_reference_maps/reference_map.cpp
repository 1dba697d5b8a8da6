#include "reference_map.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "somasim/error.hpp"

namespace somasim::tools {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream is(line);
  while (std::getline(is, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double to_double(const std::string& s, const std::string& path, int line) {
  try {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  throw InputError(path + ":" + std::to_string(line) + ": '" + s + "' is not a number");
}

}  // namespace

CountTable read_table(const std::string& path, const TableKey& key) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read CSV '" + path + "'");
  std::string line;
  if (!std::getline(in, line)) throw InputError("CSV '" + path + "' is empty");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::string expected =
      "source,protocol_or_part,taxel,d_bin,ttc_bin,d_lo_m,d_hi_m,ttc_lo,ttc_hi,pos_count,neg_count";
  if (line != expected)
    throw InputError("CSV '" + path + "': unexpected header '" + line + "'; expected '" + expected +
                     "'");
  struct Row {
    int d, t;
    double dlo, dhi, tlo, thi, pos, neg;
  };
  std::map<std::tuple<std::string, int>, std::vector<Row>> tables;  // (part, taxel)
  std::set<std::string> sources;
  int n = 1;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto c = split(line);
    if (c.size() != 11)
      throw InputError(path + ":" + std::to_string(n) + ": expected 11 columns, got " +
                       std::to_string(c.size()));
    sources.insert(c[0]);
    if (c[0] != key.source) continue;
    const int taxel = static_cast<int>(to_double(c[2], path, n));
    if (!key.part.empty() && c[1] != key.part) continue;
    if (key.taxel >= 0 && taxel != key.taxel) continue;
    tables[{c[1], taxel}].push_back(
        Row{static_cast<int>(to_double(c[3], path, n)), static_cast<int>(to_double(c[4], path, n)),
            to_double(c[5], path, n), to_double(c[6], path, n), to_double(c[7], path, n),
            to_double(c[8], path, n), to_double(c[9], path, n), to_double(c[10], path, n)});
  }
  if (tables.empty()) {
    std::string msg = "no table in '" + path + "' matches source '" + key.source + "'";
    if (!key.part.empty()) msg += ", part '" + key.part + "'";
    if (key.taxel >= 0) msg += ", taxel " + std::to_string(key.taxel);
    msg += "; sources:";
    for (const auto& s : sources) msg += " " + s;
    throw InputError(msg);
  }
  if (tables.size() > 1) {
    std::string msg = std::to_string(tables.size()) + " tables match source '" + key.source +
                      "'; choose one with --part and --taxel:";
    int shown = 0;
    for (const auto& [k, rows] : tables) {
      if (shown++ == 12) {
        msg += " ...";
        break;
      }
      msg += " (" + std::get<0>(k) + ", " + std::to_string(std::get<1>(k)) + ")";
    }
    throw InputError(msg);
  }
  const auto& [k, rows] = *tables.begin();
  CountTable t;
  t.source = key.source;
  t.part = std::get<0>(k);
  t.taxel = std::get<1>(k);
  for (const auto& r : rows) {
    t.d_bins = std::max(t.d_bins, r.d + 1);
    t.ttc_bins = std::max(t.ttc_bins, r.t + 1);
  }
  if (static_cast<int>(rows.size()) != t.d_bins * t.ttc_bins)
    throw InputError("table (" + t.part + ", " + std::to_string(t.taxel) + ") of '" + path +
                     "' has " + std::to_string(rows.size()) + " rows; expected " +
                     std::to_string(t.d_bins) + " x " + std::to_string(t.ttc_bins));
  t.d_edges.assign(t.d_bins + 1, 0);
  t.ttc_edges.assign(t.ttc_bins + 1, 0);
  t.pos.assign(rows.size(), 0);
  t.neg.assign(rows.size(), 0);
  for (const auto& r : rows) {
    if (r.d < 0 || r.t < 0) throw InputError("negative bin index in '" + path + "'");
    t.d_edges[r.d] = r.dlo;
    t.d_edges[r.d + 1] = r.dhi;
    t.ttc_edges[r.t] = r.tlo;
    t.ttc_edges[r.t + 1] = r.thi;
    const std::size_t i = static_cast<std::size_t>(r.d) * t.ttc_bins + r.t;
    t.pos[i] = r.pos;
    t.neg[i] = r.neg;
  }
  return t;
}

}  // namespace somasim::tools
