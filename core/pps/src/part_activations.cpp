#include "somasim/pps/part_activations.hpp"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "somasim/error.hpp"

namespace somasim::pps {

void PartActivations::build_index(const TaxelValues& input, const SkinPart& part,
                                  const std::string& who) {
  std::unordered_map<std::string, std::size_t> at;
  std::set<std::string> parts;
  for (std::size_t i = 0; i < input.labels.size(); ++i) {
    at.emplace(input.labels[i], i);
    parts.insert(input.labels[i].substr(0, input.labels[i].rfind('/')));
  }
  if (!parts.contains(part.name)) {
    std::string names;  // somasim_pps does not link the core's diagnostics (join_names)
    for (const auto& p : parts) names += (names.empty() ? "" : ", ") + p;
    throw RunError(who + ": 'activations' has no values for skin part '" + part.name +
                   "' (labels 'part/id' of " + names + ")");
  }
  index_.clear();
  for (int id : part.taxel_ids) {
    const std::string label = part.name + "/" + std::to_string(id);
    const auto it = at.find(label);
    if (it == at.end())
      throw RunError(who + ": 'activations' has no value labelled '" + label + "' (skin part '" +
                     part.name + "' has " + std::to_string(part.taxel_ids.size()) + " taxels)");
    index_.push_back(it->second);
  }
  labels_ = input.labels;
  part_ = part.name;
  ids_ = part.taxel_ids;
}

std::span<const double> PartActivations::select(const TaxelValues& input, const SkinPart& part,
                                                const std::string& who) {
  const auto& v = input.values;
  if (v.empty()) return {};
  if (input.labels.empty()) {
    if (v.size() != part.taxel_ids.size())
      throw RunError(who + ": 'activations' has " + std::to_string(v.size()) +
                     " values, but skin part '" + part.name + "' has " +
                     std::to_string(part.taxel_ids.size()) + " taxels");
    return v;
  }
  if (input.labels.size() != v.size())
    throw RunError(who + ": 'activations' has " + std::to_string(input.labels.size()) +
                   " labels but " + std::to_string(v.size()) + " values");
  if (part.name != part_ || part.taxel_ids != ids_ || input.labels != labels_)
    build_index(input, part, who);
  values_.resize(index_.size());
  for (std::size_t k = 0; k < index_.size(); ++k) values_[k] = v[index_[k]];
  return values_;
}

}  // namespace somasim::pps
