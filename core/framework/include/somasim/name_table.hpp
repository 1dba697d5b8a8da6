#pragma once
/// @file
/// One name table per enumeration, serving a parameter's choices, parsing and writing.
///
/// A library declares the table next to its enumeration, as a function found by
/// argument-dependent lookup:
/// @code
///   enum class Profile { kLinear, kMinimumJerk };
///   inline constexpr NamedValue<Profile> kProfileNames[] = {
///       {Profile::kLinear, "linear"}, {Profile::kMinimumJerk, "minimum_jerk"}};
///   constexpr std::span<const NamedValue<Profile>> name_table(Profile) { return kProfileNames; }
/// @endcode
/// A config field of type Profile then offers exactly these names (see somasim/config.hpp).
#include <concepts>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "somasim/error.hpp"

namespace somasim {

/// One entry of an enumeration's name table.
template <class E>
struct NamedValue {
  E value;
  std::string_view name;
};

/// An enumeration with a name table reachable by `name_table(E{})`.
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  { name_table(e) } -> std::convertible_to<std::span<const NamedValue<E>>>;
};

/// The names of every value, in table order.
template <NamedEnum E>
std::vector<std::string> enum_names() {
  std::vector<std::string> names;
  for (const NamedValue<E>& entry : name_table(E{})) names.emplace_back(entry.name);
  return names;
}

/// The name of `value`; a value missing from the table is a bug (aborts).
template <NamedEnum E>
std::string_view enum_name(E value) {
  for (const NamedValue<E>& entry : name_table(E{}))
    if (entry.value == value) return entry.name;
  SOMASIM_CHECK(false, "enumeration value missing from its name table");
  return {};
}

/// The value named `name`, or nullopt.
template <NamedEnum E>
std::optional<E> parse_enum(std::string_view name) {
  for (const NamedValue<E>& entry : name_table(E{}))
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

/// "a, b, c": the names for messages.
template <NamedEnum E>
std::string enum_names_joined() {
  std::string text;
  for (const NamedValue<E>& entry : name_table(E{}))
    text += (text.empty() ? "" : ", ") + std::string(entry.name);
  return text;
}

}  // namespace somasim
