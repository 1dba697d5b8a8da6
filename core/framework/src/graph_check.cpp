#include "graph_check.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

namespace somasim::detail {
namespace {

std::string library_of(const Experiment& exp, const std::string& node) {
  const NodeSpec* n = exp.find_node(node);
  return n && n->spec && !n->spec->library_path.empty() ? n->spec->library_path : "built in";
}

std::vector<std::string> node_names(const Experiment& exp) {
  std::vector<std::string> names;
  for (const auto& n : exp.nodes) names.push_back(n.name);
  return names;
}

// Finds the producer's output port, or reports why it cannot.
const PortSpec* resolve_output(const Experiment& exp, const std::string& node,
                               const std::string& port, const SourceLocation& where,
                               const std::string& consumer, const std::string& key,
                               Diagnostics& diags) {
  const NodeSpec* producer = exp.find_node(node);
  if (!producer) {
    diags.add(where, consumer, key,
              "no node '" + node + "'" + did_you_mean(node, node_names(exp)) +
                  "; nodes: " + join_names(node_names(exp)));
    return nullptr;
  }
  if (!producer->spec) return nullptr;  // its own error was reported already
  const PortSpec* out = producer->spec->find_port(port, PortDirection::Output);
  if (!out) {
    const auto outs = producer->spec->port_names(PortDirection::Output);
    diags.add(where, consumer, key,
              "node '" + node + "' (plugin '" + producer->plugin + "') has no output '" + port +
                  "'" + did_you_mean(port, outs) +
                  "; outputs: " + (outs.empty() ? "(none)" : join_names(outs)));
  }
  return out;
}

void check_inputs(const Experiment& exp, Diagnostics& diags, bool allow_harness) {
  for (const auto& n : exp.nodes) {
    if (!n.spec) continue;
    for (const auto& w : n.inputs) {
      const std::string key = "inputs." + w.port;
      const PortSpec* in = n.spec->find_port(w.port, PortDirection::Input);
      if (!in) {
        const auto ins = n.spec->port_names(PortDirection::Input);
        diags.add(w.where, n.name, key,
                  "plugin '" + n.plugin + "' has no input '" + w.port + "'" +
                      did_you_mean(w.port, ins) +
                      "; inputs: " + (ins.empty() ? "(none)" : join_names(ins)));
        continue;
      }
      if (allow_harness && w.from_node == "harness") continue;
      const PortSpec* out =
          resolve_output(exp, w.from_node, w.from_port, w.where, n.name, key, diags);
      if (out && out->type->name != in->type->name)
        diags.add(w.where, n.name, key,
                  "type mismatch: input '" + w.port + "' takes '" + in->type->name + "' but '" +
                      w.from_node + "." + w.from_port + "' gives '" + out->type->name + "'");
      else if (out && out->type->size_of != in->type->size_of)
        diags.add(w.where, n.name, key,
                  fmt::format("type '{}' is {} bytes in '{}' ({}) but {} bytes in '{}' ({}): the "
                              "two plugin libraries were built against different definitions "
                              "of it; rebuild both against this somasim",
                              in->type->name, out->type->size_of, w.from_node,
                              library_of(exp, w.from_node), in->type->size_of, n.name,
                              n.spec->library_path.empty() ? "built in" : n.spec->library_path));
    }
    for (const auto& p : n.spec->ports()) {
      if (p.direction != PortDirection::Input || p.optional) continue;
      const bool wired = std::any_of(n.inputs.begin(), n.inputs.end(),
                                     [&](const InputWire& w) { return w.port == p.name; });
      // A malformed wire (or inputs map) was reported already: "not wired" would be noise.
      const bool reported =
          std::any_of(diags.items().begin(), diags.items().end(), [&](const Diagnostic& d) {
            return d.node == n.name && (d.key == "inputs" || d.key == "inputs." + p.name ||
                                        d.key.rfind("inputs." + p.name + ".", 0) == 0);
          });
      if (!wired && !reported)
        diags.add(n.where, n.name, "inputs." + p.name,
                  "required input is not wired (expected 'node.port' giving '" + p.type->name +
                      "': " + p.doc + ")");
    }
  }
}

void check_records(const Experiment& exp, Diagnostics& diags) {
  for (const auto& r : exp.records) {
    const PortSpec* out = resolve_output(exp, r.node, r.port, r.where, "", "record", diags);
    if (out && !out->type->make_recorder)
      diags.add(r.where, "", "record",
                "port '" + r.node + "." + r.port + "' of type '" + out->type->name +
                    "' cannot be recorded (its type has neither CSV columns nor a recorder)");
    // Video is for ports whose type's recorder writes one (images).
    else if (out && r.as == RecordAs::kVideo && !out->type->records_video)
      diags.add(r.where, "", "record",
                "port '" + r.node + "." + r.port + "' of type '" + out->type->name +
                    "' cannot be recorded as video (only image ports can; record it as files)");
  }
}

// Kahn's algorithm over undelayed edges; smallest file index first among ready nodes.
void order_nodes(Experiment& exp, Diagnostics& diags) {
  const int n = static_cast<int>(exp.nodes.size());
  std::map<std::string, int> index;
  for (int i = 0; i < n; ++i) index[exp.nodes[i].name] = i;
  std::vector<std::vector<int>> consumers(n);
  std::vector<int> indegree(n, 0);
  for (int i = 0; i < n; ++i)
    for (const auto& w : exp.nodes[i].inputs) {
      auto it = index.find(w.from_node);
      if (w.delayed || it == index.end()) continue;
      consumers[it->second].push_back(i);
      ++indegree[i];
    }
  std::vector<int> ready;
  for (int i = 0; i < n; ++i)
    if (indegree[i] == 0) ready.push_back(i);
  exp.order.clear();
  while (!ready.empty()) {
    auto it = std::min_element(ready.begin(), ready.end());
    const int i = *it;
    ready.erase(it);
    exp.order.push_back(i);
    for (int c : consumers[i])
      if (--indegree[c] == 0) ready.push_back(c);
  }
  if (static_cast<int>(exp.order.size()) == n) return;
  // Report one cycle: walk undelayed inputs among the unordered nodes until a node repeats.
  std::vector<bool> ordered(n, false);
  for (int i : exp.order) ordered[i] = true;
  int start = 0;
  while (ordered[start]) ++start;
  std::vector<int> path;
  std::vector<int> pos(n, -1);
  int cur = start;
  while (pos[cur] < 0) {
    pos[cur] = static_cast<int>(path.size());
    path.push_back(cur);
    for (const auto& w : exp.nodes[cur].inputs) {
      auto it = index.find(w.from_node);
      if (!w.delayed && it != index.end() && !ordered[it->second]) {
        cur = it->second;
        break;
      }
    }
  }
  std::string cycle;
  for (std::size_t k = pos[cur]; k < path.size(); ++k)
    cycle = exp.nodes[path[k]].name + " -> " + cycle;
  cycle = exp.nodes[cur].name + " -> " + cycle;
  cycle.resize(cycle.size() - 4);
  diags.add(exp.nodes[cur].where, exp.nodes[cur].name, "inputs",
            "cycle without a delayed edge: " + cycle +
                " (data flows left to right; mark one of these inputs as {from: node.port, "
                "delayed: true} to read the previous tick's value)");
}

}  // namespace

void check_graph(Experiment& exp, Diagnostics& diags, bool allow_harness_inputs) {
  check_inputs(exp, diags, allow_harness_inputs);
  check_records(exp, diags);
  order_nodes(exp, diags);
}

}  // namespace somasim::detail
