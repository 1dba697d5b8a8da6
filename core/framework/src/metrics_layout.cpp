#include "somasim/metrics_layout.hpp"

#include <algorithm>
#include <map>

namespace somasim {

namespace {

bool is_run_key(std::string_view key) {
  return std::find(kRunMetricKeys.begin(), kRunMetricKeys.end(), key) != kRunMetricKeys.end();
}

void flatten_into(const std::string& prefix, const nlohmann::json& value,
                  std::vector<std::pair<std::string, nlohmann::json>>& out) {
  if (value.is_object()) {
    for (const auto& [key, sub] : value.items()) flatten_into(prefix + "." + key, sub, out);
  } else if (!value.is_array()) {
    out.emplace_back(prefix, value);
  }
}

}  // namespace

std::vector<std::pair<std::string, nlohmann::json>> node_metrics_by_flat_name(
    const nlohmann::json& metrics) {
  std::vector<std::pair<std::string, nlohmann::json>> out;
  const auto nodes = metrics.find("nodes");
  if (nodes == metrics.end() || !nodes->is_object()) return out;
  struct Entry {
    std::string node, key;
    const nlohmann::json* value;
    bool qualified;
  };
  std::vector<Entry> entries;
  std::map<std::string, int> reporters;
  for (const auto& [node, values] : nodes->items())
    if (values.is_object())
      for (const auto& [key, value] : values.items()) ++reporters[key];
  for (const auto& [node, values] : nodes->items())
    if (values.is_object())
      for (const auto& [key, value] : values.items())
        entries.push_back(
            {node, key, &value, reporters[key] > 1 || is_run_key(key) || key == "nodes"});
  // Plain names must not collide with anything else once flattened (a node named like another
  // node's metric, a metric with a '.' in its name): every entry whose flattened names meet
  // another's is qualified, until the names are distinct.
  for (std::size_t round = 0; round <= entries.size(); ++round) {
    std::map<std::string, std::vector<std::size_t>> owners;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Entry& e = entries[i];
      std::vector<std::pair<std::string, nlohmann::json>> leaves;
      flatten_into(e.qualified ? e.node + "." + e.key : e.key, *e.value, leaves);
      if (leaves.empty()) leaves.emplace_back(e.qualified ? e.node + "." + e.key : e.key, nullptr);
      for (const auto& leaf : leaves) owners[leaf.first].push_back(i);
    }
    bool changed = false;
    for (const auto& [name, who] : owners)
      if (who.size() > 1)
        for (std::size_t i : who)
          if (!entries[i].qualified) entries[i].qualified = changed = true;
    if (!changed) break;
  }
  for (const Entry& e : entries)
    out.emplace_back(e.qualified ? e.node + "." + e.key : e.key, *e.value);
  return out;
}

std::optional<nlohmann::json> find_metric(const nlohmann::json& metrics, std::string_view name) {
  if (!metrics.is_object()) return std::nullopt;
  // Candidates are tried from the longest head: "node.metric" before "node".
  auto descend = [&](const nlohmann::json& root,
                     std::string_view rest) -> std::optional<nlohmann::json> {
    const nlohmann::json* at = &root;
    while (!rest.empty()) {
      const std::size_t dot = rest.find('.');
      const std::string key(rest.substr(0, dot));
      if (!at->is_object() || !at->contains(key)) return std::nullopt;
      at = &(*at)[key];
      rest = dot == std::string_view::npos ? std::string_view{} : rest.substr(dot + 1);
    }
    return *at;
  };
  std::vector<std::pair<std::string, nlohmann::json>> heads;
  for (const auto key : kRunMetricKeys)
    if (metrics.contains(std::string(key))) heads.emplace_back(key, metrics[std::string(key)]);
  for (auto& entry : node_metrics_by_flat_name(metrics)) heads.push_back(std::move(entry));
  std::optional<nlohmann::json> best;
  std::size_t best_length = 0;
  for (const auto& [head, value] : heads) {
    if (name == head) return value;
    if (name.size() > head.size() && name.starts_with(head) && name[head.size()] == '.' &&
        head.size() > best_length) {
      if (auto found = descend(value, name.substr(head.size() + 1))) {
        best = std::move(found);
        best_length = head.size();
      }
    }
  }
  return best;
}

std::vector<std::pair<std::string, nlohmann::json>> flatten_metrics(const nlohmann::json& metrics) {
  std::vector<std::pair<std::string, nlohmann::json>> out;
  if (!metrics.is_object()) return out;
  for (const auto key : kRunMetricKeys)
    if (metrics.contains(std::string(key)))
      flatten_into(std::string(key), metrics[std::string(key)], out);
  for (const auto& [name, value] : node_metrics_by_flat_name(metrics))
    flatten_into(name, value, out);
  return out;
}

}  // namespace somasim
