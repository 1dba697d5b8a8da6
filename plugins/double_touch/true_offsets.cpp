#include "true_offsets.hpp"

#include <limits>

#include "somasim/error.hpp"
#include "somasim/pps/stimulus.hpp"

namespace somasim::plugins {

namespace {

double d_of(const Stimulus& s, const Eigen::Vector3d& taxel, const Eigen::Vector3d& normal) {
  pps::TaxelPose pose;
  pose.position = taxel;
  pose.normal = normal;
  pps::Stimulus st;
  st.position = s.position;
  st.velocity = s.velocity;
  st.radius = s.radius;
  const auto f = pps::to_taxel_frame(pose, st);
  return pps::compute_d_ttc(f.p, f.v, pps::TtcDefinition::kUnsigned).d;
}

const SkinPart* find_part(const SkinTaxels& t, const std::string& name) {
  for (const auto& p : t.parts)
    if (p.name == name) return &p;
  return nullptr;
}

int find_taxel(const SkinPart& p, int id) {
  for (std::size_t k = 0; k < p.taxel_ids.size(); ++k)
    if (p.taxel_ids[k] == id) return static_cast<int>(k);
  return -1;
}

}  // namespace

void TrueOffsetTracker::update_layout(const SkinTaxels& truth, TaxelValues& out) {
  std::size_t n = 0;
  for (const auto& p : truth.parts) n += p.taxel_ids.size();
  if (out.labels.size() == n && index_.size() == n) return;
  out.labels.clear();
  index_.clear();
  for (const auto& p : truth.parts)
    for (int id : p.taxel_ids) {
      const std::string label = p.name + "/" + std::to_string(id);
      index_[label] = out.labels.size();
      out.labels.push_back(label);
    }
  out.values.assign(out.labels.size(), std::numeric_limits<double>::quiet_NaN());
  for (const auto& [label, s] : sums_) {
    const auto it = index_.find(label);
    if (it != index_.end() && s.count > 0) out.values[it->second] = s.sum / s.count;
  }
}

void TrueOffsetTracker::add_event(const ContactEvent& event, const SkinTaxels& truth,
                                  const SkinTaxels* believed, const Stimulus& perceived,
                                  const Stimulus& true_stimulus, TaxelValues& out) {
  const SkinPart* tp = find_part(truth, event.body_part);
  if (!tp) return;  // a part this source does not report
  const SkinPart* bp = believed ? find_part(*believed, event.body_part) : tp;
  if (!bp)
    throw RunError("true offsets: skin part '" + event.body_part +
                   "' is not in the 'believed_taxels' input");
  for (int id : event.touched_taxels) {
    const int kt = find_taxel(*tp, id);
    if (kt < 0) continue;
    const int kb = find_taxel(*bp, id);
    if (kb < 0)
      throw RunError("true offsets: taxel " + std::to_string(id) + " of part '" + event.body_part +
                     "' is not in the 'believed_taxels' input");
    const auto ut = static_cast<std::size_t>(kt), ub = static_cast<std::size_t>(kb);
    const double d_perceived = d_of(perceived, bp->positions[ub], bp->normals[ub]);
    const double d_true = d_of(true_stimulus, tp->positions[ut], tp->normals[ut]);
    const std::string label = event.body_part + "/" + std::to_string(id);
    Sum& s = sums_[label];
    s.sum += d_perceived - d_true;
    ++s.count;
    ++samples_;
    const auto it = index_.find(label);
    if (it != index_.end()) out.values[it->second] = s.sum / s.count;
  }
}

}  // namespace somasim::plugins
