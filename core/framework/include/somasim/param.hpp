#pragma once
/// @file
/// Plugin parameters: the schema a plugin declares (name, type, unit, default, range, doc)
/// and the validated values a node receives.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "somasim/error.hpp"

namespace somasim {

enum class ParamType { Bool, Int, Double, String, DoubleList, StringList };

/// Human-readable type name used in messages and docs ("a number", "a list of numbers", ...).
const char* param_type_name(ParamType type);

/// A parameter value. Int is 64-bit; DoubleList is a YAML sequence of numbers; StringList is a
/// YAML sequence of words or, for convenience on the command line, one string of words
/// separated by spaces or commas (`parts: left_forearm right_palm`).
using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>,
                                std::vector<std::string>>;

/// Renders a value for messages, docs and the resolved experiment file.
std::string param_value_str(const ParamValue& value);

/// The declaration of one parameter. Built with chainable setters:
/// `spec.add_double("speed_min").unit_is("m/s").defaults(0.05).range(0, 10).describe("...")`.
struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Double;
  std::string unit;                         ///< SI unit, e.g. "m", "s", "rad", "m/s"; "" if none
  std::optional<ParamValue> default_value;  ///< nullopt: the parameter is required
  std::optional<double> min, max;           ///< inclusive range for numbers (each list element)
  std::vector<std::string> choices;  ///< allowed values of a String (StringList element), if fixed
  std::optional<std::size_t> list_size;      ///< required length of a list
  std::optional<std::size_t> max_list_size;  ///< longest list accepted
  /// Integers: the range the member's type holds (set by config fields; not shown in docs,
  /// where min/max give the meaningful range).
  std::optional<std::int64_t> int_min, int_max;
  /// A String that is "name: value" text (e.g. joint angles): a flat YAML map is accepted too and
  /// read as the text "k1: v1, k2: v2" (so `--set 'P={a: 1, b: 2}'` works without inner quotes).
  bool map_as_text = false;
  std::string doc;

  ParamSpec& unit_is(std::string u) {
    unit = std::move(u);
    return *this;
  }
  ParamSpec& defaults(ParamValue v) {
    default_value = std::move(v);
    return *this;
  }
  ParamSpec& range(double lo, double hi) {
    min = lo;
    max = hi;
    return *this;
  }
  ParamSpec& at_least(double lo) {
    min = lo;
    return *this;
  }
  ParamSpec& one_of(std::vector<std::string> c) {
    choices = std::move(c);
    return *this;
  }
  ParamSpec& accepts_map_as_text() {
    map_as_text = true;
    return *this;
  }
  ParamSpec& size(std::size_t n) {
    list_size = n;
    return *this;
  }
  ParamSpec& describe(std::string d) {
    doc = std::move(d);
    return *this;
  }
  bool required() const { return !default_value.has_value(); }
};

/// Validated parameter values of one node: every declared parameter has a value of its type.
class Params {
 public:
  Params() = default;
  explicit Params(std::map<std::string, ParamValue> values) : values_(std::move(values)) {}

  /// Typed access. T is bool, std::int64_t, int, double, std::string, std::vector<double> or
  /// std::vector<std::string>.
  /// Asking for an undeclared name or a wrong type is a bug in the plugin (aborts).
  template <class T>
  T get(const std::string& name) const;

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::map<std::string, ParamValue>& values() const { return values_; }

 private:
  const ParamValue& raw(const std::string& name) const;
  std::map<std::string, ParamValue> values_;
};

template <class T>
T Params::get(const std::string& name) const {
  const ParamValue& v = raw(name);
  if constexpr (std::is_same_v<T, int>) {
    SOMASIM_CHECK(std::holds_alternative<std::int64_t>(v), "parameter is not an integer");
    const std::int64_t i = std::get<std::int64_t>(v);
    if (!std::in_range<int>(i))
      throw InputError("parameter '" + name + "': value " + std::to_string(i) +
                       " does not fit a 32-bit integer");
    return static_cast<int>(i);
  } else {
    SOMASIM_CHECK(std::holds_alternative<T>(v), "parameter read with the wrong type");
    return std::get<T>(v);
  }
}

}  // namespace somasim
