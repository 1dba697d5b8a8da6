#include "somasim/plugin_spec.hpp"

namespace somasim {

ParamSpec& PluginSpec::add(const std::string& name, ParamType type) {
  SOMASIM_CHECK(find_param(name) == nullptr, "parameter declared twice");
  ParamSpec p;
  p.name = name;
  p.type = type;
  params_.push_back(std::move(p));
  return params_.back();
}

ParamSpec& PluginSpec::add_param(ParamSpec spec) {
  SOMASIM_CHECK(find_param(spec.name) == nullptr, "parameter declared twice");
  params_.push_back(std::move(spec));
  return params_.back();
}

const ParamSpec* PluginSpec::find_param(const std::string& name) const {
  for (const auto& p : params_)
    if (p.name == name) return &p;
  return nullptr;
}

const PortSpec* PluginSpec::find_port(const std::string& name, PortDirection direction) const {
  for (const auto& p : ports_)
    if (p.name == name && p.direction == direction) return &p;
  return nullptr;
}

std::vector<std::string> PluginSpec::param_names() const {
  std::vector<std::string> names;
  for (const auto& p : params_) names.push_back(p.name);
  return names;
}

std::vector<std::string> PluginSpec::port_names(PortDirection direction) const {
  std::vector<std::string> names;
  for (const auto& p : ports_)
    if (p.direction == direction) names.push_back(p.name);
  return names;
}

}  // namespace somasim
