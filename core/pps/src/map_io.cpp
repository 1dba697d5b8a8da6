#include "somasim/pps/map_io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "somasim/atomic_file.hpp"
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
  // Range-checked as a 64-bit value: 4294967304 must not read as 8.
  if (!v.is_number_integer() ||
      (v.is_number_unsigned() ? v.get<std::uint64_t>() > std::numeric_limits<int>::max()
                              : (v.get<std::int64_t>() < std::numeric_limits<int>::min() ||
                                 v.get<std::int64_t>() > std::numeric_limits<int>::max())))
    fail(source, "'" + where + key + "' is " + v.dump() + ", expected an integer in [" +
                     std::to_string(std::numeric_limits<int>::min()) + ", " +
                     std::to_string(std::numeric_limits<int>::max()) + "]");
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

json part_to_json(const LearnedState& s, bool with_model) {
  json j;
  const bool distance_only = s.model == PpsModel::kDistanceOnly;
  j["body_part"] = s.body_part;
  if (with_model) j["model"] = to_string(s.model);
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
    json taxel = {{"id", t.id},
                  {"position", {p.x(), p.y(), p.z()}},
                  {"normal", {n.x(), n.y(), n.z()}},
                  {"pos", t.pos},
                  {"neg", t.neg}};
    if (t.contact_events > 0) {  // optional: the contact offset estimator's evidence
      taxel["contact_d_sum"] = t.contact_d_sum;
      taxel["contact_events"] = t.contact_events;
    }
    taxels.push_back(std::move(taxel));
  }
  j["taxels"] = std::move(taxels);
  return j;
}

// One body part's object: `p` is the key prefix of its members in messages ("" at the top level
// of a version 1/2 file, "parts[k]." in a version 3 file). `with_model`: "model" is required.
LearnedState part_from_json(const json& j, const std::string& p, bool with_model,
                            const std::string& source) {
  LearnedState s;
  if (with_model) {
    const json& m = member(j, "model", p, source);
    if (!m.is_string() || !parse_pps_model(m.get<std::string>(), s.model))
      fail(source, "'" + p + "model' is " + m.dump() + ", expected \"d_ttc\" or \"distance_only\"");
  }
  const bool distance_only = s.model == PpsModel::kDistanceOnly;
  const json& bp = member(j, "body_part", p, source);
  if (!bp.is_string()) fail(source, "'" + p + "body_part' is " + bp.dump() + ", expected a string");
  s.body_part = bp.get<std::string>();

  const json& g = member(j, "grid", p, source);
  if (!g.is_object()) fail(source, "'" + p + "grid' is " + type_name(g) + ", expected an object");
  const std::string gp = p + "grid.";
  s.grid.d_min = get_number(g, "d_min", gp, source);
  s.grid.d_max = get_number(g, "d_max", gp, source);
  s.grid.d_bins = get_int(g, "d_bins", gp, source);
  if (distance_only) {
    s.grid = distance_only_grid(s.grid);
  } else {
    s.grid.ttc_min = get_number(g, "ttc_min", gp, source);
    s.grid.ttc_max = get_number(g, "ttc_max", gp, source);
    s.grid.ttc_bins = get_int(g, "ttc_bins", gp, source);
  }
  if (const std::string e = s.grid.validate(); !e.empty())
    fail(source, "invalid " + p + "grid: " + e);

  const json& pz = member(j, "parzen", p, source);
  if (!pz.is_object())
    fail(source, "'" + p + "parzen' is " + type_name(pz) + ", expected an object");
  const std::string pp = p + "parzen.";
  s.parzen.sigma_scale = get_number(pz, "sigma_scale", pp, source);
  if (const std::string e = s.parzen.validate(); !e.empty())
    fail(source, "invalid " + p + "parzen: " + e);
  const json& anchor = member(pz, "anchor", pp, source);
  if (!anchor.is_string() || !parse_kernel_anchor(anchor.get<std::string>(), s.parzen.anchor))
    fail(source,
         "'" + pp + "anchor' is " + anchor.dump() + ", expected \"centre\" or \"lower_edge\"");

  const json& taxels = member(j, "taxels", p, source);
  if (!taxels.is_array())
    fail(source, "'" + p + "taxels' is " + type_name(taxels) + ", expected an array");
  const std::size_t n = s.grid.size();
  s.taxels.reserve(taxels.size());
  for (std::size_t k = 0; k < taxels.size(); ++k) {
    const std::string where = p + "taxels[" + std::to_string(k) + "].";
    const json& t = taxels[k];
    if (!t.is_object())
      fail(source, "'" + p + "taxels[" + std::to_string(k) + "]' is " + type_name(t) +
                       ", expected an object");
    LearnedTaxel lt;
    lt.id = get_int(t, "id", where, source);
    for (std::size_t q = 0; q < s.taxels.size(); ++q)
      if (s.taxels[q].id == lt.id)
        fail(source, "'" + where + "id' is " + std::to_string(lt.id) + ", which " + p + "taxels[" +
                         std::to_string(q) + "] already uses; expected unique ids");
    lt.pose_link.position = get_vec3(t, "position", where, source);
    lt.pose_link.normal = get_vec3(t, "normal", where, source);
    if (!(lt.pose_link.normal.norm() > 0.0))
      fail(source, "'" + where + "normal' is zero, expected a non-zero vector");
    lt.pos = get_counts(t, "pos", where, n, s.grid, source);
    lt.neg = get_counts(t, "neg", where, n, s.grid, source);
    if (t.contains("contact_events") || t.contains("contact_d_sum")) {
      const int events = get_int(t, "contact_events", where, source);
      if (events < 0)
        fail(source, "'" + where + "contact_events' is " + std::to_string(events) +
                         ", expected a count >= 0");
      lt.contact_events = static_cast<std::uint32_t>(events);
      lt.contact_d_sum = get_number(t, "contact_d_sum", where, source);
      if (!std::isfinite(lt.contact_d_sum))
        fail(source, "'" + where + "contact_d_sum' is not finite, expected a number [m]");
    }
    s.taxels.push_back(std::move(lt));
  }
  return s;
}

// "format" and "version" of any file; returns the version.
int check_header(const json& j, const std::string& source) {
  if (!j.is_object()) fail(source, "top level is " + type_name(j) + ", expected a JSON object");
  const json& fmt = member(j, "format", "", source);
  if (!fmt.is_string() || fmt.get<std::string>() != kMapFormat)
    fail(source, "'format' is " + fmt.dump() + ", expected \"" + kMapFormat + "\"");
  const json& ver = member(j, "version", "", source);
  if (!ver.is_number_integer() ||
      (ver.get<int>() != kMapFormatVersion && ver.get<int>() != kMapFormatVersionModel &&
       ver.get<int>() != kMapFormatVersionParts))
    fail(source, "'version' is " + ver.dump() + ", expected " + std::to_string(kMapFormatVersion) +
                     ", " + std::to_string(kMapFormatVersionModel) + " or " +
                     std::to_string(kMapFormatVersionParts));
  return ver.get<int>();
}

// Every body part of a file of any version, in file order (checked: unique names).
std::vector<LearnedState> all_parts(const json& j, const std::string& source) {
  const int version = check_header(j, source);
  std::vector<LearnedState> out;
  if (version != kMapFormatVersionParts) {
    out.push_back(part_from_json(j, "", version == kMapFormatVersionModel, source));
    return out;
  }
  const json& parts = member(j, "parts", "", source);
  if (!parts.is_array())
    fail(source, "'parts' is " + type_name(parts) + ", expected an array of body parts");
  if (parts.empty()) fail(source, "'parts' is empty, expected at least one body part");
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string p = "parts[" + std::to_string(k) + "]";
    if (!parts[k].is_object())
      fail(source, "'" + p + "' is " + type_name(parts[k]) + ", expected an object");
    LearnedState s = part_from_json(parts[k], p + ".", true, source);
    for (std::size_t q = 0; q < out.size(); ++q)
      if (out[q].body_part == s.body_part)
        fail(source, "'" + p + ".body_part' is \"" + s.body_part + "\", which parts[" +
                         std::to_string(q) + "] already uses; expected unique body parts");
    out.push_back(std::move(s));
  }
  return out;
}

std::string part_names(const std::vector<LearnedState>& parts) {
  std::string out;
  for (const LearnedState& s : parts) out += (out.empty() ? "" : " ") + s.body_part;
  return out;
}

void check_model(const LearnedState& s, const std::optional<PpsModel>& expected, bool name_part,
                 const std::string& source) {
  if (expected && *expected != s.model)
    fail(source, (name_part ? "body part \"" + s.body_part + "\": model" : std::string("model")) +
                     " is \"" + to_string(s.model) + "\", expected \"" + to_string(*expected) +
                     "\"");
}

template <typename Input>
json parse_json(Input&& in, const std::string& source) {
  try {
    return json::parse(std::forward<Input>(in));
  } catch (const json::exception& e) {  // parse_error, and out_of_range for huge numbers
    throw InputError(source + ": not valid JSON (" + e.what() + ")");
  }
}

json read_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) &&
      !std::filesystem::is_regular_file(path, ec))  // (opening a FIFO blocks)
    throw InputError(path + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open for reading");
  return parse_json(in, path);
}

void write_json_file(const json& j, const std::string& path) {
  try {
    write_file_atomically(path, j.dump(2) + '\n');
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace

json to_json(const LearnedState& s) {
  const bool distance_only = s.model == PpsModel::kDistanceOnly;
  json j;
  j["format"] = kMapFormat;
  j["version"] = distance_only ? kMapFormatVersionModel : kMapFormatVersion;
  j.update(part_to_json(s, distance_only));
  return j;
}

json to_json(const std::vector<LearnedState>& parts) {
  if (parts.size() == 1) return to_json(parts.front());
  json j;
  j["format"] = kMapFormat;
  j["version"] = kMapFormatVersionParts;
  json arr = json::array();
  for (const LearnedState& s : parts) arr.push_back(part_to_json(s, true));
  j["parts"] = std::move(arr);
  return j;
}

LearnedState from_json(const json& j, const std::string& source, const LoadExpectations& expect) {
  const int version = check_header(j, source);
  if (version != kMapFormatVersionParts) {
    // Model first (as before): a file of the other model is rejected before anything else.
    LearnedState s = part_from_json(j, "", version == kMapFormatVersionModel, source);
    check_model(s, expect.model, false, source);
    if (expect.body_part && *expect.body_part != s.body_part)
      fail(source, "body part is \"" + s.body_part + "\", expected \"" + *expect.body_part + "\"");
    if (expect.taxel_count && *expect.taxel_count != s.taxels.size())
      fail(source, "has " + std::to_string(s.taxels.size()) + " taxels, expected " +
                       std::to_string(*expect.taxel_count));
    return s;
  }
  std::vector<LearnedState> parts = all_parts(j, source);
  std::size_t k = 0;
  if (expect.body_part) {
    while (k < parts.size() && parts[k].body_part != *expect.body_part) ++k;
    if (k == parts.size())
      fail(source, "has no body part \"" + *expect.body_part + "\" (it has: " + part_names(parts) +
                       "), expected \"" + *expect.body_part + "\"");
  } else if (parts.size() != 1) {
    fail(source, "has " + std::to_string(parts.size()) + " body parts (" + part_names(parts) +
                     "), expected one (name the body part to load)");
  }
  LearnedState& s = parts[k];
  check_model(s, expect.model, true, source);
  if (expect.taxel_count && *expect.taxel_count != s.taxels.size())
    fail(source, "body part \"" + s.body_part + "\" has " + std::to_string(s.taxels.size()) +
                     " taxels, expected " + std::to_string(*expect.taxel_count));
  return std::move(s);
}

std::vector<LearnedState> parts_from_json(const json& j, const std::string& source,
                                          const PartsExpectations& expect) {
  std::vector<LearnedState> parts = all_parts(j, source);
  const bool single = parts.size() == 1 && expect.body_parts.size() == 1;
  if (single && parts.front().body_part != expect.body_parts.front())
    fail(source, "body part is \"" + parts.front().body_part + "\", expected \"" +
                     expect.body_parts.front() + "\"");
  if (!expect.body_parts.empty()) {
    std::string wanted;
    for (const std::string& name : expect.body_parts) wanted += (wanted.empty() ? "" : " ") + name;
    std::vector<LearnedState> picked;
    picked.reserve(expect.body_parts.size());
    for (const std::string& name : expect.body_parts) {
      auto it = std::find_if(parts.begin(), parts.end(),
                             [&](const LearnedState& s) { return s.body_part == name; });
      if (it == parts.end())
        fail(source, "has no body part \"" + name + "\" (it has: " + part_names(parts) +
                         "), expected every body part of \"" + wanted + "\"");
      picked.push_back(*it);
    }
    parts = std::move(picked);
  }
  for (const LearnedState& s : parts) check_model(s, expect.model, !single, source);
  return parts;
}

void save_learned_state(const LearnedState& state, const std::string& path) {
  write_json_file(to_json(state), path);
}

void save_learned_parts(const std::vector<LearnedState>& parts, const std::string& path) {
  write_json_file(to_json(parts), path);
}

LearnedState load_learned_state(const std::string& path, const LoadExpectations& expect) {
  return from_json(read_json_file(path), path, expect);
}

std::vector<LearnedState> load_learned_parts(const std::string& path,
                                             const PartsExpectations& expect) {
  return parts_from_json(read_json_file(path), path, expect);
}

std::vector<LearnedState> parse_learned_parts(const std::string& text, const std::string& source,
                                              const PartsExpectations& expect) {
  return parts_from_json(parse_json(text, source), source, expect);
}

}  // namespace somasim::pps
