#include "yarp_skin_replay.hpp"

#include <algorithm>
#include <charconv>
#include <set>

#include <fmt/format.h>

#include "somasim/skin/layout_file.hpp"

namespace somasim::plugins {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// "LEFT=RIGHT" split, or false.
bool split_pair(const std::string& item, std::string& left, std::string& right) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) return false;
  left = trim(item.substr(0, eq));
  right = trim(item.substr(eq + 1));
  return !left.empty() && !right.empty();
}

}  // namespace

template <class V>
void YarpSkinReplay::Config::visit(V& v) {
  v.block(log);
  v.field("parts", parts)
      .doc(
          "iCub skin part = body part name, e.g. [left_forearm=left_forearm, right_hand="
          "right_palm] (the iCub part by name or SkinPart id: 1 left_hand, 2 left_forearm, "
          "3 left_upper_arm, 4 right_hand, 5 right_forearm, 6 right_upper_arm, 7 front_torso); "
          "empty: every part keeps its iCub name. Contacts on other parts are counted and "
          "left out");
  v.field("layout_files", layout_files)
      .doc(
          "body part = skin layout file (somasim layout files or the iCub's skinGui positions "
          "files), relative to the experiment file: taxel ids become the ids of their virtual "
          "taxels (modules); ids not in the layout are counted as unknown_taxels");
  v.field("min_taxels", min_taxels)
      .range(1, 100000)
      .doc(
          "a contact touches its part only with at least this many taxels (the released PPS "
          "code: 3)");
  v.field("new_event_after_s", new_event_after_s)
      .unit("s")
      .at_least(0.0)
      .doc(
          "a touch is a new event when its part was untouched this long before (0: every "
          "line's contact is an event)");
  v.field("keep_events_s", keep_events_s)
      .unit("s")
      .at_least(0.0)
      .doc("how long events stay in the output's recent list");
}

template <class V>
void YarpSkinReplay::Ports::visit(V& v) {
  v.port("events", events, "contact events at the recorded times (the skin plugin's format)");
}

PluginSpec YarpSkinReplay::spec() {
  return make_plugin_spec<Config, Ports>(
      "yarp_skin_replay",
      "Replays the iCub skin's contact lists (yarpdatadumper log of /skinManager/skin_events:o) "
      "as skin contact events at their recorded times.");
}

void YarpSkinReplay::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  read_part_map(ctx);
  read_layouts(ctx);
  log_ = read_replay_log(ctx, config_, config_.log, recordings::DumpContent::kBottle);
  decode(ctx);
  cursor_ = std::make_unique<recordings::ReplayCursor>(log_.entries, config_.log.offset_s);
  log_timeline(ctx, log_);
}

void YarpSkinReplay::read_part_map(NodeContext& ctx) {
  if (config_.parts.empty()) {
    for (int id = 1; recordings::icub_skin_part_name(id); ++id)
      part_of_skin_part_[id] = std::string(*recordings::icub_skin_part_name(id));
    return;
  }
  for (const std::string& item : config_.parts) {
    std::string left, right;
    if (!split_pair(item, left, right))
      config_error(ctx, config_, config_.parts,
                   fmt::format("expected 'ICUB_PART=BODY_PART' items, got '{}'", item));
    std::optional<int> id = recordings::icub_skin_part_id(left);
    int number = 0;
    if (!id) {
      const auto [p, ec] = std::from_chars(left.data(), left.data() + left.size(), number);
      if (ec == std::errc() && p == left.data() + left.size() &&
          recordings::icub_skin_part_name(number))
        id = number;
    }
    if (!id) {
      std::string names;
      for (int k = 1; recordings::icub_skin_part_name(k); ++k)
        names +=
            fmt::format("{}{} ({})", k > 1 ? ", " : "", *recordings::icub_skin_part_name(k), k);
      config_error(ctx, config_, config_.parts,
                   fmt::format("'{}' is not an iCub skin part; expected one of: {}", left, names));
    }
    if (part_of_skin_part_.count(*id))
      config_error(ctx, config_, config_.parts,
                   fmt::format("iCub skin part '{}' is mapped twice",
                               *recordings::icub_skin_part_name(*id)));
    part_of_skin_part_[*id] = right;
  }
}

void YarpSkinReplay::read_layouts(NodeContext& ctx) {
  std::set<std::string> mapped;
  for (const auto& [id, part] : part_of_skin_part_) mapped.insert(part);
  for (const std::string& item : config_.layout_files) {
    std::string part, file;
    if (!split_pair(item, part, file))
      config_error(ctx, config_, config_.layout_files,
                   fmt::format("expected 'BODY_PART=FILE' items, got '{}'", item));
    if (!mapped.count(part))
      config_error(
          ctx, config_, config_.layout_files,
          fmt::format("body part '{}' is not among the replayed parts (see 'parts')", part));
    if (layouts_.count(part))
      config_error(ctx, config_, config_.layout_files,
                   fmt::format("body part '{}' has two layout files", part));
    const std::filesystem::path path = ctx.resolve_input_path(file);
    if (const std::string why = input_file_problem(path); !why.empty())
      config_error(ctx, config_, config_.layout_files,
                   fmt::format("layout file '{}' {}", file, why));
    try {
      layouts_.emplace(part, skin::load_layout_file(path, part, -1));
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.layout_files, e.what());
    }
  }
}

void YarpSkinReplay::decode(NodeContext& ctx) {
  contacts_.reserve(log_.entries.size());
  const std::string file = (log_.folder / "data.log").string();
  for (const recordings::DumpEntry& e : log_.entries) {
    try {
      contacts_.push_back(recordings::decode_skin_contact_list(
          recordings::parse_bottle(e.content, e.content_column)));
    } catch (const recordings::BottleSyntaxError& err) {
      config_error(ctx, config_, config_.log.log,
                   fmt::format("{}:{}:{}: {}", file, e.line, err.column(), err.what()));
    }
  }
}

void YarpSkinReplay::emit(double t, const std::string& part,
                          const recordings::SkinContactRecord& c) {
  ContactEvent e;
  e.id = next_event_id_++;
  e.time_s = t;
  e.first_touch_s = t;
  e.body_part = part;
  e.contact_point_link = c.centre_of_pressure;
  if (c.normal.norm() > 1e-9) e.contact_normal_link = c.normal.normalized();
  PartState& state = parts_[part];
  const auto layout = layouts_.find(part);
  std::set<int> ids;
  for (int taxel : c.taxels) {
    if (layout == layouts_.end()) {
      ids.insert(taxel);
      continue;
    }
    const skin::SkinLayout& l = layout->second;
    const auto it = std::find(l.ids.begin(), l.ids.end(), taxel);
    if (it == l.ids.end()) {
      ++state.unknown_taxels;
      continue;
    }
    const auto index = static_cast<std::size_t>(it - l.ids.begin());
    ids.insert(l.virtual_taxels[static_cast<std::size_t>(l.module[index])].id);
  }
  e.touched_taxels.assign(ids.begin(), ids.end());
  ++state.events;
  ports_.events->recent.push_back(std::move(e));
}

void YarpSkinReplay::step(NodeContext& ctx) {
  const double now = ctx.time_s();
  for (const recordings::DumpEntry& e : cursor_->advance_to(now)) {
    const auto index = static_cast<std::size_t>(&e - log_.entries.data());
    const double t = cursor_->due_time(e);
    for (const recordings::SkinContactRecord& c : contacts_[index]) {
      const auto part = part_of_skin_part_.find(c.skin_part);
      if (part == part_of_skin_part_.end()) {
        ++unmapped_contacts_[c.skin_part];
        continue;
      }
      if (static_cast<int>(c.taxels.size()) < config_.min_taxels) {
        ++small_contacts_;
        continue;
      }
      PartState& state = parts_[part->second];
      ++state.contacts;
      if (config_.new_event_after_s == 0.0 || t - state.last_touch_s >= config_.new_event_after_s)
        emit(t, part->second, c);
      state.last_touch_s = t;
    }
  }
  auto& recent = ports_.events->recent;
  recent.erase(std::remove_if(recent.begin(), recent.end(),
                              [&](const ContactEvent& ev) {
                                return ev.time_s < now - config_.keep_events_s &&
                                       ev.id + 1 != next_event_id_;
                              }),
               recent.end());
}

void YarpSkinReplay::finish(NodeContext& ctx) {
  if (!cursor_) return;
  report_replay(ctx, log_, *cursor_);
  nlohmann::json parts = nlohmann::json::object();
  for (const auto& [name, s] : parts_)
    parts[name] = {
        {"contacts", s.contacts}, {"events", s.events}, {"unknown_taxels", s.unknown_taxels}};
  ctx.report_metric("parts", parts);
  nlohmann::json unmapped = nlohmann::json::object();
  for (const auto& [id, n] : unmapped_contacts_)
    unmapped[recordings::icub_skin_part_name(id) ? std::string(*recordings::icub_skin_part_name(id))
                                                 : fmt::format("skin part {}", id)] = n;
  ctx.report_metric("unmapped_contacts", unmapped);
  ctx.report_metric("small_contacts", small_contacts_);
}

}  // namespace somasim::plugins
