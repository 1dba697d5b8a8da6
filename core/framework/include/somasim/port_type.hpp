#pragma once
/// @file
/// Run-time descriptions of port value types.
///
/// A type T can travel on a port once `PortTraits<T>` is specialised with:
///   - `static constexpr const char* name` — the type's identity across shared libraries;
///   - optionally `static constexpr const char* header` — where it is declared (for
///     `somasim plugins describe`), e.g. "somasim/skin/ports.hpp";
///   - optionally `static void copy(T& dst, const T& src)` — a deep copy, for types whose
///     `operator=` shares storage (e.g. a cv::Mat image); delayed edges copy with it. Without
///     it, `dst = src`;
///   - optionally `static std::vector<std::string> csv_columns(const T&)` (column headers with SI
///     units, e.g. "d [m]") and `static void csv_write(const T&, std::string& row)` (appends
///     ",v1,v2,..." — one leading comma per column), which make the port recordable as CSV;
///   - or `static std::unique_ptr<PortRecorder> recorder(const T* value, const RecordTarget&)`,
///     a recorder of its own (an image port writes PNGs); it takes precedence over CSV;
///   - and `static constexpr bool records_video = true` when that recorder writes a video for
///     `RecordTarget::video` (`record: [{port: ..., as: video}]`; image ports).
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

namespace somasim {

template <class T>
struct PortTraits;  // specialise for each port type (see port_types.hpp)

/// Writes one recorded output port of a run into the run folder.
class PortRecorder {
 public:
  virtual ~PortRecorder() = default;
  /// Records the port's value after a step of its producer at sim time `time_s` [s].
  virtual void write(double time_s) = 0;
  /// Writes out everything buffered; called at the end of a run, also after a failure. Throws
  /// RunError (naming the file) when the data cannot be written; the run then fails.
  virtual void flush() = 0;
};

/// Where a recorder writes: files named `stem` + an extension in `dir` (the run folder), e.g.
/// `world.joint_state.csv`; a recorder that writes many files makes `dir / stem` a folder.
struct RecordTarget {
  std::filesystem::path dir;
  std::string stem;      ///< "NODE.PORT"
  bool video = false;    ///< `as: video`: one video file `stem`.mp4 (image ports only)
  double rate_hz = 0.0;  ///< the producing node's step rate [Hz] (a video's frame rate)
};

struct PortTypeInfo;
/// The framework's CSV recorder of a port whose type has csv_columns/csv_write.
std::unique_ptr<PortRecorder> make_csv_recorder(const PortTypeInfo& type, const void* value,
                                                const RecordTarget& target);

/// Type-erased operations on a port value. Identity is the name (not the address), because
/// every shared library has its own copy of this table.
struct PortTypeInfo {
  std::string name;
  std::string header;       ///< the header declaring the type ("" if not given)
  std::size_t size_of = 0;  ///< sizeof(T) in the library that declared the port (wiring checks)
  std::shared_ptr<void> (*create)() = nullptr;         ///< a default-constructed value
  void (*copy)(void* dst, const void* src) = nullptr;  ///< deep copy (delayed edges)
  std::vector<std::string> (*csv_columns)(const void* value) = nullptr;
  void (*csv_write)(const void* value, std::string& row) = nullptr;
  /// Null: the port cannot be recorded.
  std::unique_ptr<PortRecorder> (*make_recorder)(const PortTypeInfo& type, const void* value,
                                                 const RecordTarget& target) = nullptr;
  bool records_video = false;  ///< its recorder writes a video when asked (PortTraits)
};

namespace detail {
template <class T, class = void>
struct HasCsv : std::false_type {};
template <class T>
struct HasCsv<T, std::void_t<decltype(PortTraits<T>::csv_columns(std::declval<const T&>()))>>
    : std::true_type {};
template <class T, class = void>
struct HasHeader : std::false_type {};
template <class T>
struct HasHeader<T, std::void_t<decltype(PortTraits<T>::header)>> : std::true_type {};
template <class T, class = void>
struct HasCopy : std::false_type {};
template <class T>
struct HasCopy<
    T, std::void_t<decltype(PortTraits<T>::copy(std::declval<T&>(), std::declval<const T&>()))>>
    : std::true_type {};
template <class T, class = void>
struct HasRecorder : std::false_type {};
template <class T>
struct HasRecorder<T, std::void_t<decltype(PortTraits<T>::recorder(
                          std::declval<const T*>(), std::declval<const RecordTarget&>()))>>
    : std::true_type {};
}  // namespace detail

/// The PortTypeInfo of T (one instance per shared library).
template <class T>
const PortTypeInfo& port_type() {
  static_assert(
      requires { PortTraits<T>::name; },
      "T is not a port type here: include the header that declares its PortTraits "
      "(somasim/plugin.hpp brings double and Eigen::Vector3d; the domain types are in "
      "somasim/robot/ports.hpp, somasim/skin/ports.hpp, somasim/pps/ports.hpp, "
      "somasim/render/ports.hpp, ...) or specialise PortTraits<T> for your own type");
  static const PortTypeInfo info = [] {
    PortTypeInfo i;
    i.name = PortTraits<T>::name;
    i.size_of = sizeof(T);
    if constexpr (detail::HasHeader<T>::value) i.header = PortTraits<T>::header;
    if constexpr (requires { PortTraits<T>::records_video; })
      i.records_video = PortTraits<T>::records_video;
    i.create = [] { return std::shared_ptr<void>(std::make_shared<T>()); };
    if constexpr (detail::HasCopy<T>::value) {
      i.copy = [](void* dst, const void* src) {
        PortTraits<T>::copy(*static_cast<T*>(dst), *static_cast<const T*>(src));
      };
    } else {
      i.copy = [](void* dst, const void* src) {
        *static_cast<T*>(dst) = *static_cast<const T*>(src);
      };
    }
    if constexpr (detail::HasCsv<T>::value) {
      i.csv_columns = [](const void* v) {
        return PortTraits<T>::csv_columns(*static_cast<const T*>(v));
      };
      i.csv_write = [](const void* v, std::string& row) {
        PortTraits<T>::csv_write(*static_cast<const T*>(v), row);
      };
      i.make_recorder = &make_csv_recorder;
    }
    if constexpr (detail::HasRecorder<T>::value) {
      i.make_recorder = [](const PortTypeInfo&, const void* v, const RecordTarget& target) {
        return PortTraits<T>::recorder(static_cast<const T*>(v), target);
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
