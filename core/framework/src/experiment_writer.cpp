// Writing an experiment back out: the resolved YAML of a run, and Graphviz DOT.
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "somasim/experiment.hpp"

namespace somasim {

namespace {
void emit_value(YAML::Emitter& out, const ParamValue& v) {
  if (const auto* list = std::get_if<std::vector<double>>(&v)) {
    out << YAML::Flow << YAML::BeginSeq;
    for (double d : *list) out << fmt::format("{}", d);
    out << YAML::EndSeq;
  } else if (const auto* words = std::get_if<std::vector<std::string>>(&v)) {
    out << YAML::Flow << YAML::BeginSeq;
    for (const auto& w : *words) out << YAML::DoubleQuoted << w;
    out << YAML::EndSeq;
  } else if (const auto* s = std::get_if<std::string>(&v)) {
    out << YAML::DoubleQuoted << *s;
  } else {
    out << param_value_str(v);
  }
}
}  // namespace

std::string Experiment::resolved_yaml() const {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "experiment" << YAML::Value << name;
  if (!description.empty()) out << YAML::Key << "description" << YAML::Value << description;
  out << YAML::Key << "seed" << YAML::Value << seed;
  out << YAML::Key << "duration_s" << YAML::Value << fmt::format("{}", duration_s);
  out << YAML::Key << "base_rate_hz" << YAML::Value << fmt::format("{}", base_rate_hz);
  out << YAML::Key << "base_dir" << YAML::Value << base_dir.string();
  if (!plugin_libraries.empty()) {
    out << YAML::Key << "plugin_libraries" << YAML::Value << YAML::BeginSeq;
    for (const auto& l : plugin_libraries) out << l;
    out << YAML::EndSeq;
  }
  if (!robots.empty()) {
    out << YAML::Key << "robots" << YAML::Value << YAML::BeginMap;
    for (const auto& r : robots) out << YAML::Key << r.name << YAML::Value << r.file.string();
    out << YAML::EndMap;
  }
  out << YAML::Key << "nodes" << YAML::Value << YAML::BeginMap;
  for (const auto& n : nodes) {
    out << YAML::Key << n.name << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "plugin" << YAML::Value << n.plugin;
    out << YAML::Key << "rate_hz" << YAML::Value << fmt::format("{}", n.rate_hz);
    out << YAML::Key << "params" << YAML::Value << YAML::BeginMap;
    for (const auto& [k, v] : n.params.values()) {
      out << YAML::Key << k << YAML::Value;
      emit_value(out, v);
    }
    out << YAML::EndMap;
    if (!n.inputs.empty()) {
      out << YAML::Key << "inputs" << YAML::Value << YAML::BeginMap;
      for (const auto& w : n.inputs) {
        out << YAML::Key << w.port << YAML::Value;
        const std::string from = w.from_node + "." + w.from_port;
        if (w.delayed)
          out << YAML::Flow << YAML::BeginMap << YAML::Key << "from" << YAML::Value << from
              << YAML::Key << "delayed" << YAML::Value << true << YAML::EndMap;
        else
          out << from;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!records.empty()) {
    out << YAML::Key << "record" << YAML::Value << YAML::BeginSeq;
    for (const auto& r : records) {
      if (r.as == RecordAs::kVideo)
        out << YAML::Flow << YAML::BeginMap << YAML::Key << "port" << YAML::Value
            << r.node + "." + r.port << YAML::Key << "as" << YAML::Value << "video" << YAML::EndMap;
      else
        out << r.node + "." + r.port;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string Experiment::graphviz() const {
  std::string dot = "digraph \"" + name + "\" {\n  rankdir=LR;\n  node [shape=record];\n";
  for (const auto& n : nodes)
    dot +=
        fmt::format("  \"{}\" [label=\"{{{}|{}|{} Hz}}\"];\n", n.name, n.name, n.plugin, n.rate_hz);
  for (const auto& n : nodes)
    for (const auto& w : n.inputs)
      dot += fmt::format("  \"{}\" -> \"{}\" [label=\"{} → {}\"{}];\n", w.from_node, n.name,
                         w.from_port, w.port, w.delayed ? ", style=dashed" : "");
  return dot + "}\n";
}

}  // namespace somasim
