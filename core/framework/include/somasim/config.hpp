#pragma once
/// @file
/// Config structs visited once. A plugin's (or a library's) options are a struct whose members
/// carry their defaults, and one `visit` names each member once with its unit, range, choices
/// and documentation. From that one list come the parameter schema (`plugins describe`,
/// validation of experiment files), the filled struct a node configures from, and the docs:
/// @code
///   struct TrackerOptions {
///     double measurement_sigma_m = 0.003;  // [m]
///     int lost_frames = 5;
///     template <class V> void visit(V& v) {
///       v.field("measurement_sigma", measurement_sigma_m).unit("m").at_least(1e-6)
///           .doc("σ of a measured position per axis");
///       v.field("lost_frames", lost_frames).range(1, 100).doc("frames before a track is lost");
///     }
///     void validate(ConfigChecks& checks) const;  // optional: cross-field checks
///   };
/// @endcode
/// Field types and their YAML form: bool; any integer type (an integer, refused where it does
/// not fit the member's type); double; std::string; std::vector<double>;
/// std::vector<std::string>; an enumeration with a name table (somasim/name_table.hpp: one of
/// its names); OutputFile and InputFile (a file name, see below). Library option structs are
/// embedded with `v.block(member)`, so each block is declared once wherever it is used.
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "somasim/name_table.hpp"
#include "somasim/param.hpp"
#include "somasim/plugin.hpp"

namespace somasim {

class ConfigFields;
class ConfigChecks;

/// A file the node writes, named by a parameter relative to the run folder. When the config is
/// filled in a run (NodeContext), the name is checked (it stays inside the run folder, is not
/// one of the run's own files — metrics.json, log.txt, experiment.resolved.yaml, manifest.json,
/// a recorder's CSV or folder, figures/, frames/ — and no other parameter of the run names the
/// same file) and `path` is set. ParamsSource (tests, tools) checks only containment and
/// collisions.
struct OutputFile {
  std::string name;            ///< as given; "" means "not written" where the default is ""
  std::filesystem::path path;  ///< the file in the run folder; empty when `name` is empty
  bool enabled() const { return !name.empty(); }
};

/// A file the node reads, named by a parameter: relative names are relative to the experiment
/// file. When the config is filled, a non-empty name must be a regular file (not a folder, FIFO
/// or device) no larger than `kMaxInputFileBytes`; `path` is set to the resolved path.
struct InputFile {
  std::string name;            ///< as given; "" means "none" where the default is ""
  std::filesystem::path path;  ///< resolved; empty when `name` is empty
  bool given() const { return !name.empty(); }
};

/// The largest input file a parameter may name [bytes] (1 GiB).
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;

/// Why `path` cannot be read as an input file ("" when it can): missing or unreadable (the
/// system's reason), not a regular file (a folder, FIFO, device or socket), or over
/// kMaxInputFileBytes. For file names that are not InputFile fields (e.g. inside a text list).
std::string input_file_problem(const std::filesystem::path& path);

/// Where a config's values come from while it is filled: the validated parameters, located
/// errors, and the run folder's file bookkeeping. NodeContext provides one (`read_config`);
/// tests may use ParamsSource.
class ConfigSource {
 public:
  virtual ~ConfigSource() = default;
  virtual const Params& params() const = 0;
  /// Throws InputError naming the key (and, for a node, the node and the key's location).
  [[noreturn]] void error(const std::string& key, const std::string& message) const {
    raise(key, message);
    std::abort();  // raise() always throws
  }
  /// The path of output file `name` (given in parameter `key`) in the run folder, claimed for
  /// this key: error() if it leaves the folder, is a run file or is claimed already.
  virtual std::filesystem::path claim_output_file(const std::string& key,
                                                  const std::string& name) = 0;
  /// `name` resolved against the experiment file's folder (absolute names unchanged).
  virtual std::filesystem::path resolve_input_file(const std::string& name) const = 0;

 protected:
  /// Throws the InputError of error().
  virtual void raise(const std::string& key, const std::string& message) const = 0;
};

/// Plain parameters without a run: output files are placed in `run_folder`, input files are
/// resolved against `base_dir`, errors name the key only. For tests and tools.
class ParamsSource : public ConfigSource {
 public:
  explicit ParamsSource(Params params, std::filesystem::path run_folder = {},
                        std::filesystem::path base_dir = {});
  const Params& params() const override { return params_; }
  std::filesystem::path claim_output_file(const std::string& key, const std::string& name) override;
  std::filesystem::path resolve_input_file(const std::string& name) const override;

 protected:
  void raise(const std::string& key, const std::string& message) const override;

 private:
  Params params_;
  std::filesystem::path run_folder_, base_dir_;
  std::vector<std::pair<std::string, std::string>> claimed_;  // (file, key)
};

/// The chainable declaration of one field, returned by ConfigFields::field.
class FieldDecl {
 public:
  explicit FieldDecl(ParamSpec& spec) : spec_(&spec) {}
  FieldDecl& unit(std::string u) {
    spec_->unit = std::move(u);
    return *this;
  }
  /// Inclusive range of a number (each element of a list).
  FieldDecl& range(double lo, double hi) {
    spec_->min = lo;
    spec_->max = hi;
    return *this;
  }
  FieldDecl& at_least(double lo) {
    spec_->min = lo;
    return *this;
  }
  FieldDecl& at_most(double hi) {
    spec_->max = hi;
    return *this;
  }
  /// Allowed words of a string (or of each element of a list of words).
  FieldDecl& one_of(std::vector<std::string> choices) {
    spec_->choices = std::move(choices);
    return *this;
  }
  /// Exact length of a list.
  FieldDecl& size(std::size_t n) {
    spec_->list_size = n;
    return *this;
  }
  /// Longest list accepted (every list has kMaxListLength at most).
  FieldDecl& max_size(std::size_t n) {
    spec_->max_list_size = n;
    return *this;
  }
  /// A string that is "name: value" text; a flat YAML map is accepted and read as that text.
  FieldDecl& map_as_text() {
    spec_->map_as_text = true;
    return *this;
  }
  /// No default: the experiment must give a value.
  FieldDecl& required() {
    spec_->default_value.reset();
    return *this;
  }
  FieldDecl& doc(std::string d) {
    spec_->doc = std::move(d);
    return *this;
  }

 private:
  ParamSpec* spec_;
};

namespace detail {

template <class T>
inline constexpr bool kIsIntField =
    std::is_integral_v<T> && !std::is_same_v<T, bool> && !std::is_same_v<T, char>;

template <class T>
struct FieldTraits;  // specialised below for every supported member type

template <>
struct FieldTraits<bool> {
  static constexpr ParamType type = ParamType::Bool;
  static ParamValue to_value(bool v) { return v; }
  static void assign(const ParamValue& v, bool& out, const std::string&, ConfigSource&) {
    out = std::get<bool>(v);
  }
};
template <>
struct FieldTraits<double> {
  static constexpr ParamType type = ParamType::Double;
  static ParamValue to_value(double v) { return v; }
  static void assign(const ParamValue& v, double& out, const std::string&, ConfigSource&) {
    out = std::get<double>(v);
  }
};
template <>
struct FieldTraits<std::string> {
  static constexpr ParamType type = ParamType::String;
  static ParamValue to_value(const std::string& v) { return v; }
  static void assign(const ParamValue& v, std::string& out, const std::string&, ConfigSource&) {
    out = std::get<std::string>(v);
  }
};
template <>
struct FieldTraits<std::vector<double>> {
  static constexpr ParamType type = ParamType::DoubleList;
  static ParamValue to_value(const std::vector<double>& v) { return v; }
  static void assign(const ParamValue& v, std::vector<double>& out, const std::string&,
                     ConfigSource&) {
    out = std::get<std::vector<double>>(v);
  }
};
template <>
struct FieldTraits<std::vector<std::string>> {
  static constexpr ParamType type = ParamType::StringList;
  static ParamValue to_value(const std::vector<std::string>& v) { return v; }
  static void assign(const ParamValue& v, std::vector<std::string>& out, const std::string&,
                     ConfigSource&) {
    out = std::get<std::vector<std::string>>(v);
  }
};
template <>
struct FieldTraits<OutputFile> {
  static constexpr ParamType type = ParamType::String;
  static ParamValue to_value(const OutputFile& v) { return v.name; }
  static void assign(const ParamValue& v, OutputFile& out, const std::string& key,
                     ConfigSource& source) {
    out.name = std::get<std::string>(v);
    out.path = out.name.empty() ? std::filesystem::path{} : source.claim_output_file(key, out.name);
  }
};
template <>
struct FieldTraits<InputFile> {
  static constexpr ParamType type = ParamType::String;
  static ParamValue to_value(const InputFile& v) { return v.name; }
  static void assign(const ParamValue& v, InputFile& out, const std::string& key,
                     ConfigSource& source);
};

/// Integers of any width: 64-bit in the schema, refused at validation where the value does not
/// fit the member's type.
template <class T>
requires kIsIntField<T>
struct FieldTraits<T> {
  static constexpr ParamType type = ParamType::Int;
  static ParamValue to_value(T v) { return static_cast<std::int64_t>(v); }
  static void assign(const ParamValue& v, T& out, const std::string& key, ConfigSource& source) {
    const std::int64_t i = std::get<std::int64_t>(v);
    if (!std::in_range<T>(i))
      source.error(key, "value " + std::to_string(i) + " does not fit the parameter's " +
                            std::to_string(8 * sizeof(T)) + "-bit integer");
    out = static_cast<T>(i);
  }
  static void bound(ParamSpec& spec) {
    constexpr auto lo = std::numeric_limits<T>::min();
    constexpr auto hi = std::numeric_limits<T>::max();
    spec.int_min = std::in_range<std::int64_t>(lo) ? static_cast<std::int64_t>(lo)
                                                   : std::numeric_limits<std::int64_t>::min();
    spec.int_max = std::in_range<std::int64_t>(hi) ? static_cast<std::int64_t>(hi)
                                                   : std::numeric_limits<std::int64_t>::max();
  }
};

template <NamedEnum E>
struct FieldTraits<E> {
  static constexpr ParamType type = ParamType::String;
  static ParamValue to_value(E v) { return std::string(enum_name(v)); }
  static void assign(const ParamValue& v, E& out, const std::string& key, ConfigSource& source) {
    const auto parsed = parse_enum<E>(std::get<std::string>(v));
    if (!parsed)
      source.error(key, "expected one of " + enum_names_joined<E>() + ", got '" +
                            std::get<std::string>(v) + "'");
    out = *parsed;
  }
  static void choices(ParamSpec& spec) { spec.choices = enum_names<E>(); }
};

template <class T>
concept HasValidate = requires(const T& c, ConfigChecks& checks) {
  c.validate(checks);
};

}  // namespace detail

/// Cross-field checks of a filled config: `fail(config.member, why)` throws the located error
/// of the parameter that member was read from (no name is written twice).
class ConfigChecks {
 public:
  ConfigChecks(const ConfigSource& source, const ConfigFields& fields)
      : source_(source), fields_(fields) {}
  template <class T>
  [[noreturn]] void fail(const T& member, const std::string& message) const {
    fail_at(&member, typeid(T), message);
  }
  template <class T>
  void require(bool condition, const T& member, const std::string& message) const {
    if (!condition) fail_at(&member, typeid(T), message);
  }

 private:
  [[noreturn]] void fail_at(const void* member, const std::type_info& type,
                            const std::string& message) const;
  const ConfigSource& source_;
  const ConfigFields& fields_;
};

/// The visitor that collects a config's fields: each field's ParamSpec (its default taken from
/// the member's value at visit time) and how to fill the member from a parameter value.
class ConfigFields {
 public:
  struct Entry {
    ParamSpec spec;
    const void* member = nullptr;          ///< the visited member (for located errors)
    const std::type_info* type = nullptr;  ///< its type (a block shares its first field's address)
    std::function<void(const ParamValue&, ConfigSource&)> assign;
  };

  /// Declares member `value` as parameter `name`; the member's current value is the default.
  template <class T>
  FieldDecl field(const std::string& name, T& value) {
    using Traits = detail::FieldTraits<T>;
    Entry& e = entries_.emplace_back();
    e.spec.name = name;
    e.spec.type = Traits::type;
    e.spec.default_value = Traits::to_value(value);
    if constexpr (requires(ParamSpec & s) { Traits::bound(s); }) Traits::bound(e.spec);
    if constexpr (requires(ParamSpec & s) { Traits::choices(s); }) Traits::choices(e.spec);
    T* member = &value;
    e.member = member;
    e.type = &typeid(T);
    e.assign = [member, name](const ParamValue& v, ConfigSource& source) {
      Traits::assign(v, *member, name, source);
    };
    return FieldDecl(e.spec);
  }

  /// Embeds a block with its own `visit` (a library option struct): its fields join this list.
  template <class Block>
  void block(Block& b) {
    b.visit(*this);
    if constexpr (detail::HasValidate<Block>) {
      const Block* p = &b;
      validators_.push_back([p](ConfigChecks& checks) { p->validate(checks); });
    }
  }

  const std::deque<Entry>& entries() const { return entries_; }
  /// The parameter name of a visited member of type `type`, or nullptr.
  const std::string* key_of(const void* member, const std::type_info& type) const;
  /// Fills every visited member from `source` (values already validated against the schema),
  /// then runs the embedded blocks' validate().
  void fill(ConfigSource& source) const;

 private:
  std::deque<Entry> entries_;
  std::vector<std::function<void(ConfigChecks&)>> validators_;
};

/// The parameter schema of config struct C (defaults from a default-constructed C).
template <class C>
std::vector<ParamSpec> config_schema() {
  C config{};
  ConfigFields fields;
  config.visit(fields);
  std::vector<ParamSpec> specs;
  for (const auto& e : fields.entries()) specs.push_back(e.spec);
  return specs;
}

/// C filled from `source` and checked (the blocks' and then C's validate()).
template <class C>
C read_config(ConfigSource& source) {
  C config{};
  ConfigFields fields;
  config.visit(fields);
  fields.fill(source);
  if constexpr (detail::HasValidate<C>) {
    ConfigChecks checks(source, fields);
    config.validate(checks);
  }
  return config;
}

/// C filled from a node's parameters (call it in configure()): errors are located at the
/// parameter in the experiment file and name the node; output files are claimed in the run.
template <class C>
C read_config(NodeContext& ctx);

/// The ConfigSource of a node (defined with NodeContext).
std::unique_ptr<ConfigSource> node_config_source(NodeContext& ctx);

template <class C>
C read_config(NodeContext& ctx) {
  const auto source = node_config_source(ctx);
  return read_config<C>(*source);
}

/// The name of the parameter `member` (a member of `config`) is read from; a member that is no
/// field of the config is a bug (aborts).
template <class C, class T>
std::string config_key(const C& config, const T& member) {
  C& visited = const_cast<C&>(config);  // the visit only takes the members' addresses
  ConfigFields fields;
  visited.visit(fields);
  const std::string* key = fields.key_of(&member, typeid(T));
  SOMASIM_CHECK(key != nullptr, "config_key: not a field of this config (a block is no field)");
  return *key;
}

/// A problem found after the config was read (e.g. against the robot model): InputError
/// located at the parameter `member` was read from, naming the node.
template <class C, class T>
[[noreturn]] void config_error(const NodeContext& ctx, const C& config, const T& member,
                               const std::string& message) {
  ctx.param_error(config_key(config, member), message);
}

}  // namespace somasim
