#pragma once
/// @file
/// What a plugin declares about itself: name, documentation, parameter schema and ports.
/// The spec drives validation, wiring checks, `somasim plugins describe` and generated docs.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "somasim/param.hpp"
#include "somasim/port_type.hpp"

namespace somasim {

class Plugin;

enum class PortDirection { Input, Output };

struct PortSpec {
  std::string name;
  PortDirection direction = PortDirection::Input;
  const PortTypeInfo* type = nullptr;
  std::string doc;
  bool optional = false;  ///< inputs only: may be left unwired
};

/// The declaration of a plugin. Plugins build it in a static `spec()` function.
class PluginSpec {
 public:
  PluginSpec(std::string name, std::string doc) : name_(std::move(name)), doc_(std::move(doc)) {}

  ParamSpec& add_bool(const std::string& name) { return add(name, ParamType::Bool); }
  ParamSpec& add_int(const std::string& name) { return add(name, ParamType::Int); }
  ParamSpec& add_double(const std::string& name) { return add(name, ParamType::Double); }
  ParamSpec& add_string(const std::string& name) { return add(name, ParamType::String); }
  ParamSpec& add_list(const std::string& name) { return add(name, ParamType::DoubleList); }
  ParamSpec& add_string_list(const std::string& name) { return add(name, ParamType::StringList); }
  /// Adds a whole declaration (config structs generate these, see somasim/config.hpp).
  ParamSpec& add_param(ParamSpec spec);

  template <class T>
  PluginSpec& input(std::string name, std::string doc, bool optional = false) {
    ports_.push_back(
        {std::move(name), PortDirection::Input, &port_type<T>(), std::move(doc), optional});
    return *this;
  }
  template <class T>
  PluginSpec& output(std::string name, std::string doc) {
    ports_.push_back({std::move(name), PortDirection::Output, &port_type<T>(), std::move(doc)});
    return *this;
  }

  const std::string& name() const { return name_; }
  const std::string& doc() const { return doc_; }
  const std::vector<ParamSpec>& params() const { return params_; }
  const std::vector<PortSpec>& ports() const { return ports_; }
  const ParamSpec* find_param(const std::string& name) const;
  const PortSpec* find_port(const std::string& name, PortDirection direction) const;
  std::vector<std::string> param_names() const;
  std::vector<std::string> port_names(PortDirection direction) const;

  /// Creates an instance; set by PluginRegistrar::add.
  std::function<std::unique_ptr<Plugin>()> factory;
  /// Path of the shared library that provided this plugin; set by the loader.
  std::string library_path;

 private:
  ParamSpec& add(const std::string& name, ParamType type);
  std::string name_, doc_;
  std::vector<ParamSpec> params_;
  std::vector<PortSpec> ports_;
};

}  // namespace somasim
