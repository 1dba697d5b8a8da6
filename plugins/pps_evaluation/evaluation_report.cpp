#include "evaluation_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "somasim/atomic_file.hpp"
#include "somasim/error.hpp"

namespace somasim::plugins {

namespace {

// Linear interpolation between the order statistics of sorted `v` (non-empty).
double percentile(const std::vector<double>& v, double q) {
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

nlohmann::json rate(std::size_t count, std::size_t of) {
  return of ? nlohmann::json(static_cast<double>(count) / static_cast<double>(of))
            : nlohmann::json();
}

// Metrics of a group of approach presentations.
nlohmann::json approach_metrics(const std::vector<const PresentationRecord*>& group) {
  std::size_t triggered = 0, skin_any = 0, skin_aimed = 0, object = 0, other = 0;
  std::vector<double> min_d, min_any, trig_d, contact_t;
  for (const auto* r : group) {
    triggered += r->triggered;
    other += r->triggered_other_part;
    skin_any += r->skin_contact_any;
    skin_aimed += r->skin_contact;
    object += r->object_contact;
    min_d.push_back(r->min_distance_m);
    min_any.push_back(r->min_distance_any_part_m);
    if (r->triggered) trig_d.push_back(r->trigger_distance_m);
    if (r->skin_contact) contact_t.push_back(r->contact_time_s - r->start_s);
  }
  const std::size_t n = group.size();
  return {{"approaches", n},
          {"triggered_rate", rate(triggered, n)},
          {"skin_contact_rate", rate(skin_any, n)},
          {"contact_rate", rate(skin_aimed, n)},
          {"object_contact_rate", rate(object, n)},
          {"other_part_trigger_rate", rate(other, n)},
          {"min_distance_m", summarize(min_d)},
          {"min_distance_any_part_m", summarize(min_any)},
          {"trigger_distance_m", summarize(trig_d)},
          {"contact_time_s", summarize(contact_t)}};
}

// Metrics of static or receding presentations (any trigger is a false one).
nlohmann::json still_metrics(const std::vector<const PresentationRecord*>& group) {
  std::size_t triggered = 0, skin_any = 0;
  std::vector<double> min_d;
  for (const auto* r : group) {
    triggered += r->triggered;
    skin_any += r->skin_contact_any;
    min_d.push_back(r->min_distance_m);
  }
  return {{"presentations", group.size()},
          {"trigger_rate", rate(triggered, group.size())},
          {"skin_contact_rate", rate(skin_any, group.size())},
          {"min_distance_m", summarize(min_d)}};
}

std::string number(double v) {
  return std::isfinite(v) ? fmt::format("{:.6g}", v) : "nan";
}

}  // namespace

nlohmann::json summarize(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  nlohmann::json s = {{"n", values.size()}};
  if (values.empty()) {
    for (const char* k : {"mean", "median", "min", "max", "p5", "p95"}) s[k] = nullptr;
    return s;
  }
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  s["mean"] = sum / static_cast<double>(values.size());
  s["median"] = percentile(values, 0.5);
  s["min"] = values.front();
  s["max"] = values.back();
  s["p5"] = percentile(values, 0.05);
  s["p95"] = percentile(values, 0.95);
  return s;
}

nlohmann::json evaluation_metrics(const std::vector<PresentationRecord>& records) {
  std::vector<const PresentationRecord*> approaches, statics, receding;
  std::map<std::string, std::vector<const PresentationRecord*>> per_part;
  std::size_t unseen = 0;
  for (const auto& r : records) {
    if (!r.seen) {
      ++unseen;
      continue;
    }
    switch (r.motion) {
      case PresentationMotion::kApproach:
        approaches.push_back(&r);
        per_part[r.body_part].push_back(&r);
        break;
      case PresentationMotion::kStatic:
        statics.push_back(&r);
        break;
      case PresentationMotion::kReceding:
        receding.push_back(&r);
        break;
    }
  }
  nlohmann::json m = approach_metrics(approaches);
  const nlohmann::json s = still_metrics(statics), rc = still_metrics(receding);
  const std::size_t still = statics.size() + receding.size();
  std::size_t false_triggers = 0;
  for (const auto* r : statics) false_triggers += r->triggered;
  for (const auto* r : receding) false_triggers += r->triggered;
  m["false_trigger_rate"] = rate(false_triggers, still);
  m["static_trigger_rate"] = s["trigger_rate"];
  m["receding_trigger_rate"] = rc["trigger_rate"];
  m["presentations"] = approaches.size() + still;
  m["presentations_not_seen"] = unseen;
  nlohmann::json parts = nlohmann::json::object();
  for (const auto& [part, group] : per_part) parts[part] = approach_metrics(group);
  m["per_part"] = parts;
  // Approaches the cameras could and could not see coming, apart (when the source checked).
  std::map<PresentationSight, std::vector<const PresentationRecord*>> per_sight;
  for (const auto* r : approaches) per_sight[r->sight].push_back(r);
  std::size_t out_of_view = 0;
  for (const auto& r : records) out_of_view += r.seen && r.sight == PresentationSight::kOutOfView;
  if (!per_sight.contains(PresentationSight::kNotChecked) || approaches.empty()) {
    m["presentations_out_of_view"] = out_of_view;
    for (const auto sight : {PresentationSight::kInView, PresentationSight::kOutOfView})
      m[presentation_sight_name(sight)] = approach_metrics(per_sight[sight]);
  }
  m["per_motion"] = {{"approach", approach_metrics(approaches)}, {"static", s}, {"receding", rc}};
  return m;
}

void write_presentations_csv(const std::filesystem::path& file,
                             const std::vector<PresentationRecord>& records) {
  std::ostringstream out;
  out << "id,motion,body_part,taxel_id,object,shape,speed [m/s],start [s],end [s],triggered,"
         "trigger_time [s],trigger_taxel_id,trigger_distance [m],min_distance "
         "[m],min_distance_any_part [m],"
         "max_activation,triggered_other_part,skin_contact,skin_contact_any_part,"
         "contact_time [s],object_contact,max_controller_speed [m/s],seen,sight\n";
  for (const auto& r : records)
    out << r.id << ',' << motion_name(r.motion) << ',' << r.body_part << ',' << r.taxel_id << ','
        << r.object << ',' << r.shape << ',' << number(r.speed) << ',' << number(r.start_s) << ','
        << number(r.end_s) << ',' << r.triggered << ',' << number(r.trigger_time_s) << ','
        << r.trigger_taxel_id << ',' << number(r.trigger_distance_m) << ','
        << number(r.min_distance_m) << ',' << number(r.min_distance_any_part_m) << ','
        << number(r.max_activation) << ',' << r.triggered_other_part << ',' << r.skin_contact << ','
        << r.skin_contact_any << ',' << number(r.contact_time_s) << ',' << r.object_contact << ','
        << number(r.max_speed) << ',' << r.seen << ',' << presentation_sight_name(r.sight) << '\n';
  try {
    write_file_atomically(file, out.str());
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace somasim::plugins
