#include "somasim/pps/map_io.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "somasim/error.hpp"

namespace somasim::pps {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InputError(source + ": " + what);
}

std::string type_name(const json& j) {
  return j.type_name();
}

const json& member(const json& obj, const char* key, const std::string& where,
                   const std::string& source) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(source, "missing key '" + where + key + "'");
  return *it;
}

double get_number(const json& obj, const char* key, const std::string& where,
                  const std::string& source) {
  const json& v = member(obj, key, where, source);
  if (!v.is_number())
    fail(source, "'" + where + key + "' is " + type_name(v) + ", expected a number");
  return v.get<double>();
}

int get_int(const json& obj, const char* key, const std::string& where, const std::string& source) {
  const json& v = member(obj, key, where, source);
  if (!v.is_number_integer())
    fail(source, "'" + where + key + "' is " + v.dump() + ", expected an integer");
  return v.get<int>();
}

Eigen::Vector3d get_vec3(const json& obj, const char* key, const std::string& where,
                         const std::string& source) {
  const json& v = member(obj, key, where, source);
  if (!v.is_array() || v.size() != 3)
    fail(source, "'" + where + key + "' is " + v.dump() + ", expected an array of 3 numbers");
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (!v[static_cast<std::size_t>(i)].is_number())
      fail(source, "'" + where + key + "' is " + v.dump() + ", expected an array of 3 numbers");
    out(i) = v[static_cast<std::size_t>(i)].get<double>();
  }
  return out;
}

std::vector<TaxelMap::Count> get_counts(const json& obj, const char* key, const std::string& where,
                                        std::size_t expected, const GridSpec& grid,
                                        const std::string& source) {
  const json& v = member(obj, key, where, source);
  if (!v.is_array())
    fail(source, "'" + where + key + "' is " + type_name(v) + ", expected an array of " +
                     std::to_string(expected) + " counts");
  if (v.size() != expected)
    fail(source, "'" + where + key + "' has " + std::to_string(v.size()) + " entries, expected " +
                     std::to_string(expected) + " (" + std::to_string(grid.d_bins) + " D bins x " +
                     std::to_string(grid.ttc_bins) + " TTC bins)");
  std::vector<TaxelMap::Count> out(expected);
  for (std::size_t i = 0; i < expected; ++i) {
    const json& c = v[i];
    const bool ok_int = c.is_number_integer() &&
                        (c.is_number_unsigned() || c.get<std::int64_t>() >= 0) &&
                        c.get<std::uint64_t>() <= std::numeric_limits<TaxelMap::Count>::max();
    if (!ok_int)
      fail(source, "'" + where + key + "[" + std::to_string(i) + "]' is " + c.dump() +
                       ", expected a non-negative integer count");
    out[i] = static_cast<TaxelMap::Count>(c.get<std::uint64_t>());
  }
  return out;
}

}  // namespace

json to_json(const LearnedState& s) {
  json j;
  const bool distance_only = s.model == PpsModel::kDistanceOnly;
  j["format"] = kMapFormat;
  j["version"] = distance_only ? kMapFormatVersionModel : kMapFormatVersion;
  if (distance_only) j["model"] = to_string(s.model);
  j["body_part"] = s.body_part;
  if (distance_only)
    j["grid"] = {{"d_min", s.grid.d_min}, {"d_max", s.grid.d_max}, {"d_bins", s.grid.d_bins}};
  else
    j["grid"] = {{"d_min", s.grid.d_min},     {"d_max", s.grid.d_max},
                 {"d_bins", s.grid.d_bins},   {"ttc_min", s.grid.ttc_min},
                 {"ttc_max", s.grid.ttc_max}, {"ttc_bins", s.grid.ttc_bins}};
  j["parzen"] = {{"sigma_scale", s.parzen.sigma_scale}, {"anchor", to_string(s.parzen.anchor)}};
  json taxels = json::array();
  for (const LearnedTaxel& t : s.taxels) {
    const Eigen::Vector3d& p = t.pose_link.position;
    const Eigen::Vector3d& n = t.pose_link.normal;
    taxels.push_back({{"id", t.id},
                      {"position", {p.x(), p.y(), p.z()}},
                      {"normal", {n.x(), n.y(), n.z()}},
                      {"pos", t.pos},
                      {"neg", t.neg}});
  }
  j["taxels"] = std::move(taxels);
  return j;
}

LearnedState from_json(const json& j, const std::string& source, const LoadExpectations& expect) {
  if (!j.is_object()) fail(source, "top level is " + type_name(j) + ", expected a JSON object");
  const json& fmt = member(j, "format", "", source);
  if (!fmt.is_string() || fmt.get<std::string>() != kMapFormat)
    fail(source, "'format' is " + fmt.dump() + ", expected \"" + kMapFormat + "\"");
  const json& ver = member(j, "version", "", source);
  if (!ver.is_number_integer() ||
      (ver.get<int>() != kMapFormatVersion && ver.get<int>() != kMapFormatVersionModel))
    fail(source, "'version' is " + ver.dump() + ", expected " + std::to_string(kMapFormatVersion) +
                     " or " + std::to_string(kMapFormatVersionModel));

  LearnedState s;
  if (ver.get<int>() == kMapFormatVersionModel) {
    const json& m = member(j, "model", "", source);
    if (!m.is_string() || !parse_pps_model(m.get<std::string>(), s.model))
      fail(source, "'model' is " + m.dump() + ", expected \"d_ttc\" or \"distance_only\"");
  }
  if (expect.model && *expect.model != s.model)
    fail(source, std::string("model is \"") + to_string(s.model) + "\", expected \"" +
                     to_string(*expect.model) + "\"");
  const bool distance_only = s.model == PpsModel::kDistanceOnly;
  const json& bp = member(j, "body_part", "", source);
  if (!bp.is_string()) fail(source, "'body_part' is " + bp.dump() + ", expected a string");
  s.body_part = bp.get<std::string>();
  if (expect.body_part && *expect.body_part != s.body_part)
    fail(source, "body part is \"" + s.body_part + "\", expected \"" + *expect.body_part + "\"");

  const json& g = member(j, "grid", "", source);
  if (!g.is_object()) fail(source, "'grid' is " + type_name(g) + ", expected an object");
  s.grid.d_min = get_number(g, "d_min", "grid.", source);
  s.grid.d_max = get_number(g, "d_max", "grid.", source);
  s.grid.d_bins = get_int(g, "d_bins", "grid.", source);
  if (distance_only) {
    s.grid = distance_only_grid(s.grid);
  } else {
    s.grid.ttc_min = get_number(g, "ttc_min", "grid.", source);
    s.grid.ttc_max = get_number(g, "ttc_max", "grid.", source);
    s.grid.ttc_bins = get_int(g, "ttc_bins", "grid.", source);
  }
  if (const std::string e = s.grid.validate(); !e.empty()) fail(source, "invalid grid: " + e);

  const json& pz = member(j, "parzen", "", source);
  if (!pz.is_object()) fail(source, "'parzen' is " + type_name(pz) + ", expected an object");
  s.parzen.sigma_scale = get_number(pz, "sigma_scale", "parzen.", source);
  if (const std::string e = s.parzen.validate(); !e.empty()) fail(source, "invalid parzen: " + e);
  const json& anchor = member(pz, "anchor", "parzen.", source);
  if (!anchor.is_string() || !parse_kernel_anchor(anchor.get<std::string>(), s.parzen.anchor))
    fail(source, "'parzen.anchor' is " + anchor.dump() + ", expected \"centre\" or \"lower_edge\"");

  const json& taxels = member(j, "taxels", "", source);
  if (!taxels.is_array()) fail(source, "'taxels' is " + type_name(taxels) + ", expected an array");
  if (expect.taxel_count && *expect.taxel_count != taxels.size())
    fail(source, "has " + std::to_string(taxels.size()) + " taxels, expected " +
                     std::to_string(*expect.taxel_count));
  const std::size_t n = s.grid.size();
  for (std::size_t k = 0; k < taxels.size(); ++k) {
    const std::string where = "taxels[" + std::to_string(k) + "].";
    const json& t = taxels[k];
    if (!t.is_object())
      fail(source,
           "'taxels[" + std::to_string(k) + "]' is " + type_name(t) + ", expected an object");
    LearnedTaxel lt;
    lt.id = get_int(t, "id", where, source);
    for (std::size_t q = 0; q < s.taxels.size(); ++q)
      if (s.taxels[q].id == lt.id)
        fail(source, "'" + where + "id' is " + std::to_string(lt.id) + ", which taxels[" +
                         std::to_string(q) + "] already uses; expected unique ids");
    lt.pose_link.position = get_vec3(t, "position", where, source);
    lt.pose_link.normal = get_vec3(t, "normal", where, source);
    if (!(lt.pose_link.normal.norm() > 0.0))
      fail(source, "'" + where + "normal' is zero, expected a non-zero vector");
    lt.pos = get_counts(t, "pos", where, n, s.grid, source);
    lt.neg = get_counts(t, "neg", where, n, s.grid, source);
    s.taxels.push_back(std::move(lt));
  }
  return s;
}

void save_learned_state(const LearnedState& state, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open for writing");
  out << to_json(state).dump(2) << '\n';
  if (!out) throw InputError(path + ": write failed");
}

LearnedState load_learned_state(const std::string& path, const LoadExpectations& expect) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open for reading");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(path + ": not valid JSON (" + e.what() + ")");
  }
  return from_json(j, path, expect);
}

}  // namespace somasim::pps
