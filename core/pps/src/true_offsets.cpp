#include "somasim/pps/true_offsets.hpp"

#include <algorithm>
#include <limits>

#include "somasim/error.hpp"

namespace somasim::pps {
namespace {

const SkinPart* find_part(const SkinTaxels& skin, const std::string& name) {
  for (const auto& p : skin.parts)
    if (p.name == name) return &p;
  return nullptr;
}

double d_of(const SkinPart& part, std::size_t k, const Stimulus& s) {
  const TaxelPose taxel{part.positions[k], part.normals[k]};
  const TaxelFrameStimulus local = to_taxel_frame(taxel, s);
  return compute_d_ttc(local.p, local.v, TtcDefinition::kUnsigned).d;
}

}  // namespace

double time_since_reaching_skin(const ContactEvent& event, const SkinTaxels& true_taxels,
                                const Stimulus& truth, double clearance, double max_s) {
  const SkinPart* part = find_part(true_taxels, event.body_part);
  if (!part) return 0.0;
  double back = 0.0;
  for (int id : event.touched_taxels) {
    const auto it = std::find(part->taxel_ids.begin(), part->taxel_ids.end(), id);
    if (it == part->taxel_ids.end()) continue;
    const auto k = static_cast<std::size_t>(it - part->taxel_ids.begin());
    const TaxelFrameStimulus local = to_taxel_frame({part->positions[k], part->normals[k]}, truth);
    if (local.p.z() < clearance && local.v.z() < 0.0)
      back = std::max(back, (clearance - local.p.z()) / -local.v.z());
  }
  return std::min(back, max_s);
}

void TrueOffsets::sync_layout(const SkinTaxels& true_taxels) {
  // Called every tick: compare names and ids (no string building) before rebuilding the labels.
  const auto same = [&] {
    if (layout_.size() != true_taxels.parts.size()) return false;
    for (std::size_t i = 0; i < layout_.size(); ++i)
      if (layout_[i].first != true_taxels.parts[i].name ||
          layout_[i].second != true_taxels.parts[i].taxel_ids)
        return false;
    return true;
  };
  if (same()) return;
  layout_.clear();
  labels_.clear();
  part_of_.clear();
  for (const auto& p : true_taxels.parts) {
    layout_.emplace_back(p.name, p.taxel_ids);
    for (int id : p.taxel_ids) {
      labels_.push_back(p.name + "/" + std::to_string(id));
      part_of_.push_back(p.name);
    }
  }
  index_.clear();
  for (std::size_t i = 0; i < labels_.size(); ++i) index_[labels_[i]] = i;
  sum_.assign(labels_.size(), 0.0);
  count_.assign(labels_.size(), 0);
}

int TrueOffsets::add_event(const ContactEvent& event, const SkinTaxels& true_taxels,
                           const SkinTaxels& believed_taxels, const Stimulus& perceived,
                           const Stimulus& truth) {
  const SkinPart* t = find_part(true_taxels, event.body_part);
  if (!t) return 0;  // a part this source does not follow
  const SkinPart* b = find_part(believed_taxels, event.body_part);
  if (!b)
    throw RunError("input 'believed_taxels' has no skin part '" + event.body_part +
                   "' (wire believed_kinematics.taxels)");
  int counted = 0;
  for (int id : event.touched_taxels) {
    const auto kt = std::find(t->taxel_ids.begin(), t->taxel_ids.end(), id);
    const auto kb = std::find(b->taxel_ids.begin(), b->taxel_ids.end(), id);
    if (kt == t->taxel_ids.end()) continue;
    if (kb == b->taxel_ids.end())
      throw RunError("input 'believed_taxels': skin part '" + event.body_part + "' has no taxel " +
                     std::to_string(id) + " (the true taxels have it)");
    const double offset = d_of(*b, static_cast<std::size_t>(kb - b->taxel_ids.begin()), perceived) -
                          d_of(*t, static_cast<std::size_t>(kt - t->taxel_ids.begin()), truth);
    const std::size_t slot = index_.at(event.body_part + "/" + std::to_string(id));
    sum_[slot] += offset;
    ++count_[slot];
    ++counted;
  }
  return counted;
}

void TrueOffsets::write(TaxelValues& out) const {
  if (out.labels != labels_) out.labels = labels_;
  out.values.resize(labels_.size());
  for (std::size_t i = 0; i < labels_.size(); ++i)
    out.values[i] = count_[i] > 0 ? sum_[i] / count_[i] : std::numeric_limits<double>::quiet_NaN();
}

std::map<std::string, std::pair<double, int>> TrueOffsets::part_means() const {
  std::map<std::string, std::pair<double, int>> out;
  for (std::size_t i = 0; i < labels_.size(); ++i) {
    if (count_[i] == 0) continue;
    auto& [sum, n] = out[part_of_[i]];
    sum += sum_[i] / count_[i];
    ++n;
  }
  for (auto& [part, m] : out) m.first /= m.second;
  return out;
}

}  // namespace somasim::pps
