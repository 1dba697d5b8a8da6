#include "true_offsets.hpp"

#include <algorithm>
#include <limits>

#include "somasim/error.hpp"

namespace somasim::plugins {
namespace {

const SkinPart* find_part(const SkinTaxels& skin, const std::string& name) {
  for (const auto& p : skin.parts)
    if (p.name == name) return &p;
  return nullptr;
}

double d_of(const SkinPart& part, std::size_t k, const pps::Stimulus& s) {
  const pps::TaxelPose taxel{part.positions[k], part.normals[k]};
  const pps::TaxelFrameStimulus local = pps::to_taxel_frame(taxel, s);
  return pps::compute_d_ttc(local.p, local.v, pps::TtcDefinition::kUnsigned).d;
}

}  // namespace

double time_since_reaching_skin(const ContactEvent& event, const SkinTaxels& true_taxels,
                                const pps::Stimulus& truth, double clearance, double max_s) {
  const SkinPart* part = find_part(true_taxels, event.body_part);
  if (!part) return 0.0;
  double back = 0.0;
  for (int id : event.touched_taxels) {
    const auto it = std::find(part->taxel_ids.begin(), part->taxel_ids.end(), id);
    if (it == part->taxel_ids.end()) continue;
    const auto k = static_cast<std::size_t>(it - part->taxel_ids.begin());
    const pps::TaxelFrameStimulus local =
        pps::to_taxel_frame({part->positions[k], part->normals[k]}, truth);
    if (local.p.z() < clearance && local.v.z() < 0.0)
      back = std::max(back, (clearance - local.p.z()) / -local.v.z());
  }
  return std::min(back, max_s);
}

void TrueOffsets::sync_layout(const SkinTaxels& true_taxels) {
  std::vector<std::string> labels, parts;
  for (const auto& p : true_taxels.parts)
    for (int id : p.taxel_ids) {
      labels.push_back(p.name + "/" + std::to_string(id));
      parts.push_back(p.name);
    }
  if (labels == labels_) return;
  labels_ = std::move(labels);
  part_of_ = std::move(parts);
  index_.clear();
  for (std::size_t i = 0; i < labels_.size(); ++i) index_[labels_[i]] = i;
  sum_.assign(labels_.size(), 0.0);
  count_.assign(labels_.size(), 0);
}

int TrueOffsets::add_event(const ContactEvent& event, const SkinTaxels& true_taxels,
                           const SkinTaxels& believed_taxels, const pps::Stimulus& perceived,
                           const pps::Stimulus& truth) {
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

}  // namespace somasim::plugins
