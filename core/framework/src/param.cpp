#include "somasim/param.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace somasim {

const char* param_type_name(ParamType type) {
  switch (type) {
    case ParamType::Bool:
      return "a boolean (true/false)";
    case ParamType::Int:
      return "an integer";
    case ParamType::Double:
      return "a number";
    case ParamType::String:
      return "a string";
    case ParamType::DoubleList:
      return "a list of numbers";
    case ParamType::StringList:
      return "a list of words";
  }
  return "?";
}

std::string param_value_str(const ParamValue& value) {
  struct Visitor {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return fmt::format("{}", d); }
    std::string operator()(const std::string& s) const { return s; }
    std::string operator()(const std::vector<double>& l) const {
      return fmt::format("[{}]", fmt::join(l, ", "));
    }
    std::string operator()(const std::vector<std::string>& l) const {
      return fmt::format("[{}]", fmt::join(l, ", "));
    }
  };
  return std::visit(Visitor{}, value);
}

const ParamValue& Params::raw(const std::string& name) const {
  auto it = values_.find(name);
  SOMASIM_CHECK(it != values_.end(), "parameter not declared in the plugin's schema");
  return it->second;
}

}  // namespace somasim
