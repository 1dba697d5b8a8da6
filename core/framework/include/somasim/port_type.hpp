#pragma once
/// @file
/// Run-time descriptions of port value types.
///
/// A type T can travel on a port once `PortTraits<T>` is specialised with:
///   - `static constexpr const char* name` — the type's identity across shared libraries;
///   - optionally `static std::vector<std::string> csv_columns(const T&)` (column headers with SI
///     units, e.g. "d [m]") and `static void csv_write(const T&, std::string& row)` (appends
///     ",v1,v2,..." — one leading comma per column), which make the port recordable.
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

namespace somasim {

template <class T>
struct PortTraits;  // specialise for each port type (see port_types.hpp)

/// Type-erased operations on a port value. Identity is the name (not the address), because
/// every shared library has its own copy of this table.
struct PortTypeInfo {
  std::string name;
  std::size_t size_of = 0;
  std::shared_ptr<void> (*create)() = nullptr;         ///< a default-constructed value
  void (*copy)(void* dst, const void* src) = nullptr;  ///< dst = src (for delayed edges)
  std::vector<std::string> (*csv_columns)(const void* value) = nullptr;  ///< null: not recordable
  void (*csv_write)(const void* value, std::string& row) = nullptr;
};

namespace detail {
template <class T, class = void>
struct HasCsv : std::false_type {};
template <class T>
struct HasCsv<T, std::void_t<decltype(PortTraits<T>::csv_columns(std::declval<const T&>()))>>
    : std::true_type {};
}  // namespace detail

/// The PortTypeInfo of T (one instance per shared library).
template <class T>
const PortTypeInfo& port_type() {
  static const PortTypeInfo info = [] {
    PortTypeInfo i;
    i.name = PortTraits<T>::name;
    i.size_of = sizeof(T);
    i.create = [] { return std::shared_ptr<void>(std::make_shared<T>()); };
    i.copy = [](void* dst, const void* src) {
      *static_cast<T*>(dst) = *static_cast<const T*>(src);
    };
    if constexpr (detail::HasCsv<T>::value) {
      i.csv_columns = [](const void* v) {
        return PortTraits<T>::csv_columns(*static_cast<const T*>(v));
      };
      i.csv_write = [](const void* v, std::string& row) {
        PortTraits<T>::csv_write(*static_cast<const T*>(v), row);
      };
    }
    return i;
  }();
  return info;
}

/// Appends ",value" with the shortest representation that reads back exactly.
inline void csv_append(std::string& row, double value) {
  fmt::format_to(std::back_inserter(row), ",{}", value);
}

}  // namespace somasim
