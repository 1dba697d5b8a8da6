#include "somasim/pps/learned_file.hpp"

#include <algorithm>

#include "somasim/error.hpp"
#include "somasim/pps/ini_export.hpp"
#include "somasim/pps/ini_import.hpp"

namespace somasim::pps {

namespace {

std::string names_of(const std::vector<LearnedState>& parts) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : " ") + p.body_part;
  return out;
}

// The .ini parts `expect` asks for, in its order.
std::vector<LearnedState> select_ini_parts(std::vector<LearnedState> all, const std::string& path,
                                           const PartsExpectations& expect) {
  if (expect.model && *expect.model != PpsModel::kDTtc)
    throw InputError(path + ": an .ini file holds (D, TTC) maps, expected \"" +
                     to_string(*expect.model) + "\" maps (set the learner's model to d_ttc)");
  if (expect.body_parts.empty()) return all;
  std::string wanted;
  for (const auto& w : expect.body_parts) wanted += (wanted.empty() ? "" : " ") + w;
  std::vector<LearnedState> out;
  for (const std::string& want : expect.body_parts) {
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const LearnedState& s) { return s.body_part == want; });
    if (it == all.end())
      throw InputError(path + ": has no body part \"" + want + "\" (it has: " + names_of(all) +
                       "), expected every body part of \"" + wanted + "\"");
    out.push_back(*it);
  }
  return out;
}

}  // namespace

LearnedFile load_learned_file(const std::string& path, const PartsExpectations& expect,
                              const ParzenSpec& ini_parzen) {
  if (is_ini_learned_file(path))
    return {select_ini_parts(import_taxels2d_ini(path, ini_parzen), path, expect), false};
  return {load_learned_parts(path, expect), true};
}

void save_learned_file(const std::vector<LearnedState>& parts, const std::string& path) {
  if (is_ini_learned_file(path))
    save_taxels2d_ini(parts, path);
  else
    save_learned_parts(parts, path);
}

}  // namespace somasim::pps
