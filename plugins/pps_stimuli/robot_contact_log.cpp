#include "robot_contact_log.hpp"

#include <algorithm>

namespace somasim::plugins {

RobotContactLog::RobotContactLog(const robot::RobotModel& model)
    : model_(model), skinned_(static_cast<std::size_t>(model.num_links()), false) {
  for (const auto& patch : model.skin_patches())
    if (patch.link >= 0 && patch.link < model.num_links())
      skinned_[static_cast<std::size_t>(patch.link)] = true;
}

std::optional<double> RobotContactLog::add(const Contacts& contacts, const ObjectStates& objects,
                                           const std::string& object, std::uint64_t presentation) {
  if (presentation != presentation_) {
    presentation_ = presentation;
    links_.clear();
  }
  newly_touched_.clear();
  std::optional<double> first;
  double newest = last_time_s_;
  for (const Contact& c : contacts.recent) {
    if (c.time_s <= last_time_s_) continue;
    newest = std::max(newest, c.time_s);
    // A link is side a whenever one body is a link.
    if (c.link_a < 0 || c.link_a >= model_.num_links() || c.object_b < 0) continue;
    const auto o = static_cast<std::size_t>(c.object_b);
    if (o >= objects.names.size() || objects.names[o] != object) continue;
    if (links_.empty()) {
      ++touching_;
      first = c.time_s;
    }
    if (!links_.insert(c.link_a).second) continue;
    newly_touched_.push_back(c.link_a);
    if (skinned_[static_cast<std::size_t>(c.link_a)]) continue;
    if (std::none_of(links_.begin(), links_.end(), [&](int l) {
          return l != c.link_a && !skinned_[static_cast<std::size_t>(l)];
        }))
      ++touching_unskinned_;
    ++unskinned_links_[model_.link(c.link_a).name];
  }
  last_time_s_ = newest;
  return first;
}

void RobotContactLog::report(NodeContext& ctx) const {
  ctx.report_metric("robot_contact_presentations", touching_);
  ctx.report_metric("robot_contact_unskinned_presentations", touching_unskinned_);
  nlohmann::json links = nlohmann::json::object();
  for (const auto& [name, n] : unskinned_links_) links[name] = n;
  ctx.report_metric("robot_contact_unskinned_links", links);
}

}  // namespace somasim::plugins
