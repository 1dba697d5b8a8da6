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

const SkinPart& believed_part(const SkinTaxels& believed_taxels, const std::string& name) {
  const SkinPart* b = find_part(believed_taxels, name);
  if (!b)
    throw RunError("input 'believed_taxels' has no skin part '" + name +
                   "' (wire believed_kinematics.taxels)");
  return *b;
}

// The touched taxels an event's offset is credited to: the one nearest the centre of pressure
// when the event carries it (nearest_point), else all of them.
std::vector<int> credited_taxels(const ContactEvent& event, const SkinPart& part) {
  if (!event.contact_point_link.allFinite()) return event.touched_taxels;
  std::vector<int> ids;
  std::vector<Eigen::Vector3d> positions;
  for (int id : event.touched_taxels) {
    const auto it = std::find(part.taxel_ids.begin(), part.taxel_ids.end(), id);
    if (it == part.taxel_ids.end()) continue;
    ids.push_back(id);
    positions.push_back(part.positions_link[static_cast<std::size_t>(it - part.taxel_ids.begin())]);
  }
  const int nearest = nearest_point(positions, event.contact_point_link);
  if (nearest < 0) return {};
  return {ids[static_cast<std::size_t>(nearest)]};
}

}  // namespace

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

int TrueOffsets::add_event_on_path(const ContactEvent& event, const SkinTaxels& true_taxels,
                                   const SkinTaxels& believed_taxels,
                                   std::span<const PathSample> path, double clearance) {
  const SkinPart* t = find_part(true_taxels, event.body_part);
  if (!t) return 0;  // a part this source does not follow
  believed_part(believed_taxels, event.body_part);
  int counted = 0;
  for (int id : credited_taxels(event, *t)) {
    const auto kt = std::find(t->taxel_ids.begin(), t->taxel_ids.end(), id);
    if (kt == t->taxel_ids.end()) continue;
    const auto it = static_cast<std::size_t>(kt - t->taxel_ids.begin());
    const TaxelPose taxel{t->positions[it], t->normals[it]};
    const auto height = [&](const PathSample& s) { return to_taxel_frame(taxel, s.truth).p.z(); };
    // The latest sample at least `clearance` out; then toward the next one to the crossing.
    std::size_t i = path.size();
    while (i > 0 && height(path[i - 1]) < clearance) --i;
    if (i == 0) continue;
    PathSample at = path[i - 1];
    if (i < path.size()) {
      const PathSample& next = path[i];
      const double h0 = height(at), h1 = height(next);
      const double w = h0 > h1 ? (h0 - clearance) / (h0 - h1) : 0.0;
      at.perceived.position += w * (next.perceived.position - at.perceived.position);
      at.truth.position += w * (next.truth.position - at.truth.position);
    }
    ContactEvent one = event;
    one.touched_taxels = {id};
    one.contact_point_link.setConstant(std::numeric_limits<double>::quiet_NaN());
    counted += add_event(one, true_taxels, believed_taxels, at.perceived, at.truth);
  }
  return counted;
}

int TrueOffsets::add_event(const ContactEvent& event, const SkinTaxels& true_taxels,
                           const SkinTaxels& believed_taxels, const Stimulus& perceived,
                           const Stimulus& truth, std::optional<double> clearance) {
  const SkinPart* t = find_part(true_taxels, event.body_part);
  if (!t) return 0;  // a part this source does not follow
  const SkinPart* b = &believed_part(believed_taxels, event.body_part);
  int counted = 0;
  for (int id : credited_taxels(event, *t)) {
    const auto kt = std::find(t->taxel_ids.begin(), t->taxel_ids.end(), id);
    const auto kb = std::find(b->taxel_ids.begin(), b->taxel_ids.end(), id);
    if (kt == t->taxel_ids.end()) continue;
    if (kb == b->taxel_ids.end())
      throw RunError("input 'believed_taxels': skin part '" + event.body_part + "' has no taxel " +
                     std::to_string(id) + " (the true taxels have it)");
    const auto it = static_cast<std::size_t>(kt - t->taxel_ids.begin());
    const auto ib = static_cast<std::size_t>(kb - b->taxel_ids.begin());
    Stimulus true_in = truth, perceived_in = perceived;
    if (clearance) {
      const TaxelPose true_taxel{t->positions[it], t->normals[it]};
      const double back = time_since_outside(std::span<const TaxelPose>(&true_taxel, 1), truth,
                                             *clearance, kOffsetMaxBackoff);
      true_in.position -= back * truth.velocity;
      perceived_in.position -= back * perceived.velocity;
    }
    const double offset = d_of(*b, ib, perceived_in) - d_of(*t, it, true_in);
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
