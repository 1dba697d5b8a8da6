#include "somasim/config.hpp"

#include <system_error>

#include "somasim/plugin.hpp"

namespace somasim {
namespace fs = std::filesystem;

void ConfigFields::fill(ConfigSource& source) const {
  const Params& params = source.params();
  for (const Entry& e : entries_) {
    SOMASIM_CHECK(params.has(e.spec.name), "config field missing from the validated parameters");
    e.assign(params.values().at(e.spec.name), source);
  }
  ConfigChecks checks(source, *this);
  for (const auto& validate : validators_) validate(checks);
}

const std::string* ConfigFields::key_of(const void* member, const std::type_info& type) const {
  for (const Entry& e : entries_)
    if (e.member == member && *e.type == type) return &e.spec.name;
  return nullptr;
}

void ConfigChecks::fail_at(const void* member, const std::type_info& type,
                           const std::string& message) const {
  const std::string* key = fields_.key_of(member, type);
  SOMASIM_CHECK(key != nullptr, "ConfigChecks::fail: not a field of this config");
  source_.error(*key, message);
}

std::string input_file_problem(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) return "does not exist (" + path.string() + ")";
  if (ec) return "cannot be read (" + path.string() + ": " + ec.message() + ")";
  if (!fs::is_regular_file(status)) {
    const char* what = fs::is_directory(status)                                     ? "a folder"
                       : fs::is_fifo(status)                                        ? "a FIFO"
                       : fs::is_character_file(status) || fs::is_block_file(status) ? "a device"
                       : fs::is_socket(status)                                      ? "a socket"
                                               : "a special file";
    return "is not a regular file (" + path.string() + " is " + what + ")";
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return "cannot be read (" + path.string() + ": " + ec.message() + ")";
  if (size > kMaxInputFileBytes)
    return "is larger than the " + std::to_string(kMaxInputFileBytes >> 20) +
           " MiB an input may have (" + path.string() + ")";
  return "";
}

namespace detail {

void FieldTraits<InputFile>::assign(const ParamValue& v, InputFile& out, const std::string& key,
                                    ConfigSource& source) {
  out.name = std::get<std::string>(v);
  out.path.clear();
  if (out.name.empty()) return;
  const fs::path path = source.resolve_input_file(out.name);
  if (const std::string why = input_file_problem(path); !why.empty())
    source.error(key, "input file '" + out.name + "' " + why);
  out.path = path;
}

}  // namespace detail

ParamsSource::ParamsSource(Params params, fs::path run_folder, fs::path base_dir)
    : params_(std::move(params)),
      run_folder_(std::move(run_folder)),
      base_dir_(std::move(base_dir)) {}

void ParamsSource::raise(const std::string& key, const std::string& message) const {
  throw InputError("key 'params." + key + "': " + message);
}

fs::path ParamsSource::claim_output_file(const std::string& key, const std::string& name) {
  const fs::path p = name;
  bool climbs = false;
  for (const auto& part : p) climbs = climbs || part == "..";
  if (p.is_absolute() || climbs)
    error(key, "output file '" + name + "' must stay inside the run folder");
  const std::string relative = p.lexically_normal().generic_string();
  for (const auto& [file, owner] : claimed_)
    if (file == relative && owner != key)
      error(key, "output file '" + name + "' is written by key 'params." + owner + "' already");
  claimed_.emplace_back(relative, key);
  return run_folder_ / relative;
}

fs::path ParamsSource::resolve_input_file(const std::string& name) const {
  const fs::path p = name;
  return p.is_absolute() ? p : (base_dir_ / p).lexically_normal();
}

namespace {

class NodeSource : public ConfigSource {
 public:
  explicit NodeSource(NodeContext& ctx) : ctx_(ctx) {}
  const Params& params() const override { return ctx_.params(); }
  fs::path claim_output_file(const std::string& key, const std::string& name) override {
    return ctx_.claim_output_file(key, name);
  }
  fs::path resolve_input_file(const std::string& name) const override {
    return ctx_.resolve_input_path(name);
  }

 protected:
  void raise(const std::string& key, const std::string& message) const override {
    ctx_.param_error(key, message);
  }

 private:
  NodeContext& ctx_;
};

}  // namespace

std::unique_ptr<ConfigSource> node_config_source(NodeContext& ctx) {
  return std::make_unique<NodeSource>(ctx);
}

}  // namespace somasim
